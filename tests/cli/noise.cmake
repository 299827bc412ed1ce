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
  ARGS noise -v ${_still})
# By default a verdict line per sensor: the terms a longer record would show
# and how long; why each was not seen only under -v.
add_test(NAME cli.noise_short_record_verdicts
  COMMAND sh -c "set -e; \"$0\" noise \"$1\" > noise_short_record_verdicts.txt
    grep -q '^accelerometer  look at  *not measured in this 3 min record: .*accel. random walk K on x, y, z; record at least [0-9]* min' noise_short_record_verdicts.txt
    grep -q '^gyroscope  *look at  *not measured in this 3 min record: .*rate random walk K on x, y, z' noise_short_record_verdicts.txt
    ! grep -q 'no stretch of the curve where it dominates' noise_short_record_verdicts.txt
    ! grep -q '^Allan deviation: overlapping' noise_short_record_verdicts.txt"
  $<TARGET_FILE:mpcal_cli> ${_still})
set_tests_properties(cli.noise_short_record_verdicts PROPERTIES LABELS cli
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
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
  ARGS noise -v ${_ten})
set_tests_properties(cli.noise_ten_minutes_no_random_walk_number cli.noise_ten_minutes_how_long
  PROPERTIES FIXTURES_REQUIRED noise_ten_minutes)
add_test(NAME cli.noise_one_record_length
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/noise_one_record_length.sh $<TARGET_FILE:mpcal_cli>
          ${_ten} ${CMAKE_CURRENT_BINARY_DIR}/noise_one_record_length)
set_tests_properties(cli.noise_one_record_length PROPERTIES
  FIXTURES_REQUIRED noise_ten_minutes LABELS cli)

# Records made from the ten minutes that no noise figure can come from (a
# stuck axis, a toggling one, a rate that changes halfway), each refused
# with one line naming it and no file left behind; and one lost sample.
set(_make ${CMAKE_CURRENT_SOURCE_DIR}/noise_make_record.sh)
foreach(_case stuck toggling rate_change one_gap long_gap)
  add_test(NAME cli.noise_make_${_case}
    COMMAND ${_make} ${_case} ${_ten} ${CMAKE_CURRENT_BINARY_DIR}/noise_${_case}.csv)
  set_tests_properties(cli.noise_make_${_case} PROPERTIES
    FIXTURES_REQUIRED noise_ten_minutes FIXTURES_SETUP noise_${_case} LABELS cli)
endforeach()
mpcal_cli_test(noise_stuck_axis EXIT 1
  MATCH "mpcal: error: .*not producing noise.*: accelerometer z: stuck at 9\\.81 m/s²" ABSENT n.json
  ARGS noise ${CMAKE_CURRENT_BINARY_DIR}/noise_stuck.csv --json n.json)
mpcal_cli_test(noise_toggling_axis EXIT 1
  MATCH "mpcal: error: .*: gyroscope x: two values only, 0\\.001 rad/s apart" ABSENT imu.yaml
  ARGS noise ${CMAKE_CURRENT_BINARY_DIR}/noise_toggling.csv --kalibr imu.yaml)
mpcal_cli_test(noise_rate_change EXIT 1
  MATCH "mpcal: error: .*: the sample rate is not uniform: 200 Hz near t = [0-9.]+ s, 100 Hz near t = [0-9.]+ s \\(the rate changes" ABSENT n.json
  ARGS noise ${CMAKE_CURRENT_BINARY_DIR}/noise_rate_change.csv --whole --json n.json)
mpcal_cli_test(noise_one_gap EXIT 0 MATCH "note: 1 gap in time \\(samples lost\\)"
  ARGS noise ${CMAKE_CURRENT_BINARY_DIR}/noise_one_gap.csv)
set_tests_properties(cli.noise_stuck_axis PROPERTIES FIXTURES_REQUIRED noise_stuck)
set_tests_properties(cli.noise_toggling_axis PROPERTIES FIXTURES_REQUIRED noise_toggling)
set_tests_properties(cli.noise_rate_change PROPERTIES FIXTURES_REQUIRED noise_rate_change)
set_tests_properties(cli.noise_one_gap PROPERTIES FIXTURES_REQUIRED noise_one_gap)
# Detection does not split a still record at a gap: the whole is refused.
mpcal_cli_test(noise_long_gap EXIT 1
  MATCH "mpcal: error: .*not uniform: .*\\(no samples for 2\\.0[0-9] s after t = 2[0-9.]+ s\\)"
  ABSENT n.json ARGS noise ${CMAKE_CURRENT_BINARY_DIR}/noise_long_gap.csv --json n.json)
set_tests_properties(cli.noise_long_gap PROPERTIES FIXTURES_REQUIRED noise_long_gap)

# Raw counts: refused without a scale; with the calibration that made them
# (simulate static's truth, an IMU file in counts), SI figures. The truth is
# a white noise of density 0.002 m/s²/√Hz and 0.0002 rad/s/√Hz stated
# one-sided (σ = ρ·√(rate/2)): N = ρ/√2, 0.001414 and 0.0001414; ten
# minutes at 100 Hz measure them to about 1 %.
mpcal_cli_test(noise_gyro_counts_refused EXIT 1 MATCH "gyroscope in physical units"
  ABSENT n.json ARGS noise ${_still} --gyro-units counts --json n.json)
set(_raw ${CMAKE_CURRENT_BINARY_DIR}/noise_counts.csv)
add_test(NAME cli.noise_counts_simulate
  COMMAND $<TARGET_FILE:mpcal_cli> simulate static --positions 1 --rest 600 --rate 100
          --noise-density 0.002 --gyro-noise-density 0.0002 --units counts --gyro
          --gyro-units counts --seed 4 -o ${_raw} --truth ${_raw}.truth.json)
set_tests_properties(cli.noise_counts_simulate PROPERTIES
  FIXTURES_SETUP noise_counts LABELS cli)
mpcal_cli_test(noise_counts_need_a_scale EXIT 1 MATCH "physical units.*--calib"
  ARGS noise ${_raw} --units counts --gyro-units counts)
mpcal_cli_test(noise_counts_calibrated_accelerometer EXIT 0
  MATCH "white noise N \\(VRW\\) +m/s²/√Hz +0\\.001(3[5-9]|4[0-8])[0-9]* "
  ARGS noise ${_raw} --calib ${_raw}.truth.json)
mpcal_cli_test(noise_counts_calibrated_gyroscope EXIT 0
  MATCH "white noise N \\(ARW\\) +rad/s/√Hz +0\\.0001(3[5-9]|4[0-8])[0-9]* "
  ARGS noise ${_raw} --calib ${_raw}.truth.json)
set_tests_properties(cli.noise_counts_need_a_scale cli.noise_counts_calibrated_accelerometer
  cli.noise_counts_calibrated_gyroscope PROPERTIES FIXTURES_REQUIRED noise_counts)

# Careless input: every bad flag value and empty path is a usage error (2);
# a file written before a later one fails is removed; help offers only what
# noise uses.
foreach(_flag json kalibr calib)
  add_test(NAME cli.noise_empty_${_flag}
    COMMAND sh -c "'${MPCAL_CLI_EXPECT}' 2 '--${_flag}.*empty' -- '$<TARGET_FILE:mpcal_cli>' noise '${_still}' --${_flag} ''")
  set_tests_properties(cli.noise_empty_${_flag} PROPERTIES LABELS cli)
endforeach()
add_test(NAME cli.noise_empty_input
  COMMAND sh -c "'${MPCAL_CLI_EXPECT}' 2 'INPUT.*empty' -- '$<TARGET_FILE:mpcal_cli>' noise ''")
add_test(NAME cli.noise_help_only_its_options
  COMMAND sh -c "'$<TARGET_FILE:mpcal_cli>' noise --help > noise_help.txt && grep -q -- '--json TEXT:PATH' noise_help.txt && grep -q -- '--kalibr TEXT:PATH' noise_help.txt && grep -q -- '--window' noise_help.txt && ! grep -Eq -- '--model|--robust|--counts-per-g|from the positions|from the turns' noise_help.txt")
set_tests_properties(cli.noise_empty_input cli.noise_help_only_its_options
  PROPERTIES LABELS cli)
mpcal_cli_test(noise_points_per_octave_nan EXIT 2 MATCH "--points-per-octave"
  ARGS noise ${_still} --points-per-octave nan)
mpcal_cli_test(noise_confidence_nan EXIT 2 MATCH "--confidence"
  ARGS noise ${_still} --confidence nan)
mpcal_cli_test(noise_json_removed_when_kalibr_fails EXIT 1 MATCH "/dev/full" ABSENT n.json
  ARGS noise ${_still} --json n.json --kalibr /dev/full)
mpcal_cli_test(noise_threshold_nan EXIT 2
  MATCH "--threshold: must be a number in \\[1, 100\\], got 'nan'"
  ARGS noise ${_still} --threshold nan)
mpcal_cli_test(noise_height_nan EXIT 2 MATCH "--height: must be a finite number"
  ARGS noise ${_still} --latitude 45 --height nan)
# A topic with a newline stays one quoted value: one update_rate in the file.
add_test(NAME cli.noise_kalibr_hostile_topic
  COMMAND sh -c "'$<TARGET_FILE:mpcal_cli>' noise '${_still}' --kalibr hostile.yaml --rostopic \"$(printf '/imu0\\nupdate_rate: 1 # x')\" >/dev/null 2>&1 && test $(grep -c '^update_rate' hostile.yaml) -eq 1 && grep -q '^rostopic: \"/imu0\\\\nupdate_rate: 1 # x\"$' hostile.yaml")
set_tests_properties(cli.noise_kalibr_hostile_topic PROPERTIES
  LABELS cli WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})

# --strict: a Kalibr value not measured on any axis is an error, no file.
mpcal_cli_test(noise_kalibr_strict_refuses_bound EXIT 1
  MATCH "mpcal: error: imu\\.yaml: --strict: accelerometer_random_walk, gyroscope_random_walk not measured on any axis"
  ABSENT imu.yaml n.json
  ARGS noise ${_still} --json n.json --kalibr imu.yaml --strict)
