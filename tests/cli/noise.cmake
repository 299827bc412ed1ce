# mpcal noise and mpcal simulate noise: the table, the files, the advice for
# a record too short, and bad input refused with one line and no output left.
set(_still ${MPCAL_TEST_DATA}/noise_still.csv)
set(_still_json ${MPCAL_TEST_DATA}/noise_still.json)

mpcal_cli_test(noise_help EXIT 0 MATCH "mpcal noise still\\.csv --json noise\\.json --kalibr imu\\.yaml"
  ARGS noise --help)
mpcal_cli_test(noise_table EXIT 0
  MATCH "white noise N \\(VRW\\) +m/s²/√Hz +0\\.001[0-9]+ .0\\.001"
  ARGS noise ${_still})
mpcal_cli_test(noise_whole_record_said EXIT 0
  MATCH "analysed: the whole record \\(detection found the sensor still throughout\\): 4500 samples"
  ARGS noise ${_still})
mpcal_cli_test(noise_gyroscope_datasheet_units EXIT 0 MATCH "°/√h"
  ARGS noise ${_still})
# Three minutes cannot show the random walk: no number, the bound, and how long.
mpcal_cli_test(noise_short_record_advice EXIT 0
  MATCH "random walk K on x, y, z: not measured .* To measure it, record at least"
  ARGS noise ${_still})
mpcal_cli_test(noise_files EXIT 0
  MATCH "wrote imu\\.yaml \\(Kalibr IMU model: the largest axis of each sensor\\)"
  ARGS noise ${_still} --json n.json --kalibr imu.yaml)
mpcal_cli_test(noise_kalibr_warns_upper_bound EXIT 0
  MATCH "mpcal: warning: imu\\.yaml: accelerometer_random_walk was not measured; the file has its upper bound"
  ARGS noise ${_still} --kalibr imu.yaml)
mpcal_cli_test(noise_whole_flag EXIT 0 MATCH "--whole: detection not run"
  ARGS noise ${_still} --whole)
mpcal_cli_test(noise_moving_session_longest_still EXIT 0
  MATCH "the longest still part, .* of [0-9]+ found by detection \\(the sensor moved\\)"
  ARGS noise ${MPCAL_TEST_DATA}/detect_four_positions.csv --units g)
# A file is read row by row and none of it held; when the sensor moved, it is
# read again for detection (standard input is held: it cannot be read twice).
mpcal_cli_test(noise_moving_session_read_again EXIT 0
  MATCH "note: the sensor moved near t = [0-9.]+ s: finding its longest still part \\(reading the log again\\)"
  ARGS noise ${MPCAL_TEST_DATA}/detect_four_positions.csv --units g)
add_test(NAME cli.noise_moving_stdin
  COMMAND sh -c "cat '${MPCAL_TEST_DATA}/detect_four_positions.csv' | '$<TARGET_FILE:mpcal_cli>' noise - --units g | grep -x '  note: the sensor moved near t = [0-9.]* s: finding its longest still part'")
add_test(NAME cli.noise_stdin_same_as_file
  COMMAND sh -c "'$<TARGET_FILE:mpcal_cli>' noise '${_still}' | tail -n +2 > noise_from_file.txt && cat '${_still}' | '$<TARGET_FILE:mpcal_cli>' noise - | tail -n +2 > noise_from_stdin.txt && grep -q 'detection found the sensor still throughout' noise_from_stdin.txt && cmp noise_from_file.txt noise_from_stdin.txt")
set_tests_properties(cli.noise_moving_stdin cli.noise_stdin_same_as_file PROPERTIES LABELS cli)

# Bad input and outputs refused before any work, nothing left behind.
mpcal_cli_test(noise_missing_file EXIT 1 MATCH "mpcal: error: .*missing\\.csv" ABSENT n.json
  ARGS noise missing.csv --json n.json)
mpcal_cli_test(noise_empty_file EXIT 1 MATCH "mpcal: error: .*empty" ABSENT n.json
  ARGS noise ${MPCAL_TEST_DATA}/bad/empty.csv --json n.json)
mpcal_cli_test(noise_binary_file EXIT 1 MATCH "not a text log" ABSENT n.json
  ARGS noise ${MPCAL_TEST_DATA}/bad/binary.bin --json n.json)
mpcal_cli_test(noise_nan EXIT 1 MATCH "non-finite value" ABSENT n.json
  ARGS noise ${MPCAL_TEST_DATA}/bad/nan.csv --json n.json)
mpcal_cli_test(noise_never_still EXIT 1 MATCH "no still part found.*--whole" ABSENT n.json
  ARGS noise ${MPCAL_TEST_DATA}/detect_always_moving.csv --units g --json n.json)
mpcal_cli_test(noise_counts_refused EXIT 1 MATCH "physical units" ABSENT n.json
  ARGS noise ${_still} --units counts --json n.json)
mpcal_cli_test(noise_json_is_input EXIT 1 MATCH "is the input file"
  ARGS noise ${_still} --json ${_still})
mpcal_cli_test(noise_kalibr_is_json EXIT 1 MATCH "is the input file" ABSENT same.yaml
  ARGS noise ${_still} --json same.yaml --kalibr same.yaml)
mpcal_cli_test(noise_output_missing_directory EXIT 1 MATCH "no/such/dir" ABSENT n.json
  ARGS noise ${_still} --json n.json --kalibr no/such/dir/imu.yaml)
mpcal_cli_test(noise_kalibr_needs_gyroscope EXIT 1 MATCH "needs the gyroscope" ABSENT imu.yaml
  ARGS noise ${MPCAL_TEST_DATA}/detect_four_positions.csv --units g --kalibr imu.yaml)
mpcal_cli_test(noise_bad_confidence EXIT 2 MATCH "--confidence" ARGS noise ${_still} --confidence 2)

# simulate noise
mpcal_cli_test(simulate_noise EXIT 0
  MATCH "Simulated a still consumer IMU \\(seed 1\\): 1800 rows over 0\\.05 h at 10 Hz"
  ARGS simulate noise --hours 0.05 --rate 10 -o s.csv --truth t.json)
mpcal_cli_test(simulate_noise_files EXIT 0 MATCH "^wrote s\\.csv and t\\.json"
  ARGS simulate noise --hours 0.05 --rate 10 -o s.csv --truth t.json)
mpcal_cli_test(simulate_noise_unknown_preset EXIT 1 MATCH "'tactical' is not one of: consumer, industrial"
  ABSENT s.csv t.json ARGS simulate noise --preset tactical -o s.csv --truth t.json)
mpcal_cli_test(simulate_noise_same_file EXIT 1 MATCH "name the same file" ABSENT s.csv
  ARGS simulate noise -o s.csv --truth s.csv)
mpcal_cli_test(simulate_noise_needs_truth EXIT 2 MATCH "--truth" ABSENT s.csv
  ARGS simulate noise -o s.csv)
mpcal_cli_test(simulate_noise_bad_rate EXIT 2 MATCH "--rate" ABSENT s.csv
  ARGS simulate noise --rate -4 -o s.csv --truth t.json)

# report --noise
mpcal_cli_test(report_noise EXIT 0 MATCH "wrote r\\.html \\(noise\\)"
  ARGS report --noise ${_still_json} -o r.html)
mpcal_cli_test(report_noise_not_a_noise_file EXIT 1 MATCH "noise file .*format" ABSENT r.html
  ARGS report --noise ${MPCAL_TEST_DATA}/bad/valid_calib.json -o r.html)

# A 10-minute simulated record (consumer preset, 100 Hz): the random
# walks cannot be measured, so no number: their bounds, and how long to record
# (the record in which a random walk at the bound would be measured 9 times in
# 10, and at half the bound).
set(_ten ${CMAKE_CURRENT_BINARY_DIR}/noise_ten_minutes.csv)
add_test(NAME cli.noise_ten_minutes_simulate
  COMMAND $<TARGET_FILE:mpcal_cli> simulate noise --hours 0.16666667 --rate 100 --seed 3
          -o ${_ten} --truth ${_ten}.truth.json)
set_tests_properties(cli.noise_ten_minutes_simulate PROPERTIES
  FIXTURES_SETUP noise_ten_minutes LABELS cli)
mpcal_cli_test(noise_ten_minutes_no_random_walk_number EXIT 0
  MATCH "rate random walk K +rad/s²/√Hz +< [0-9.e-]+ \\(not seen\\) +< [0-9.e-]+ \\(not seen\\) +< [0-9.e-]+ \\(not seen\\)"
  ARGS noise ${_ten})
mpcal_cli_test(noise_ten_minutes_how_long EXIT 0
  MATCH "gyroscope rate random walk K on x, y, z: not measured — .* this 10 min record; .* To measure it, record at least [0-9.]+ h \\(if it is as large as the bound; [0-9.]+ h if half of it\\)"
  ARGS noise ${_ten})
set_tests_properties(cli.noise_ten_minutes_no_random_walk_number cli.noise_ten_minutes_how_long
  PROPERTIES FIXTURES_REQUIRED noise_ten_minutes)
