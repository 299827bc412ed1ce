# mpcal simulate static: writes a log and its truth; refuses bad options with
# one line and leaves no file behind.
mpcal_cli_test(simulate_help EXIT 0 MATCH "mpcal simulate static --preset mti-g --seed 1 -o session.csv"
  ARGS simulate static --help)
mpcal_cli_test(simulate_needs_subcommand EXIT 2 MATCH "mpcal: error: " ARGS simulate)
mpcal_cli_test(simulate_static_summary EXIT 0
  MATCH "Simulated a hand-held mti-g session \\(seed 1\\): 10240 rows over 20\\.0 s at 512 Hz, 6 positions.*Wrote session\\.csv and the true errors to truth\\.json"
  ARGS simulate static --preset mti-g --seed 1 --positions 6 --dwell 2 --turn 1 --rest 2
       -o session.csv --truth truth.json)
mpcal_cli_test(simulate_units_any_case EXIT 0 MATCH "calibrate session.csv --units g -o"
  ARGS simulate static --units G --positions 2 --dwell 1 -o session.csv)
mpcal_cli_test(simulate_unknown_units EXIT 2 MATCH "--units" ABSENT session.csv
  ARGS simulate static --units furlongs -o session.csv)
mpcal_cli_test(simulate_unknown_preset EXIT 1
  MATCH "unknown device preset 'adxl'; known presets: colibri, inertiacube3, mti-g"
  ABSENT session.csv truth.json
  ARGS simulate static --preset adxl -o session.csv --truth truth.json)
mpcal_cli_test(simulate_zero_positions EXIT 2 MATCH "--positions"
  ABSENT session.csv ARGS simulate static --positions 0 -o session.csv)
mpcal_cli_test(simulate_zero_dwell EXIT 2 MATCH "--dwell"
  ABSENT session.csv ARGS simulate static --dwell 0 -o session.csv)
mpcal_cli_test(simulate_dwell_below_a_sample EXIT 1 MATCH "dwell_s = 0\\.001 s gives fewer than 2 samples"
  ABSENT session.csv ARGS simulate static --dwell 0.001 -o session.csv)
mpcal_cli_test(simulate_needs_output EXIT 2 MATCH "--output" ARGS simulate static --preset mti-g)
mpcal_cli_test(simulate_same_output_and_truth EXIT 1 MATCH "same file"
  ABSENT x.json ARGS simulate static -o x.json --truth x.json)
mpcal_cli_test(simulate_trials_to_stdout EXIT 1 MATCH "--trials writes numbered files"
  ARGS simulate static --trials 2 -o -)
mpcal_cli_test(simulate_missing_directory EXIT 1 MATCH "mpcal: error: "
  ABSENT truth.json ARGS simulate static --positions 2 -o no/such/dir/s.csv --truth truth.json)
mpcal_cli_test(simulate_bad_turn_on_spread EXIT 1 MATCH "one value or three"
  ABSENT s_1.csv ARGS simulate static --trials 2 --turn-on-spread 0.1,0.2 -o s.csv)

# The files themselves: a log with the documented header that reads back, and
# a calibration file; numbered files for --trials.
add_test(NAME cli.simulate_static_files
  COMMAND sh -c "set -e; rm -rf simulate_files && mkdir simulate_files && cd simulate_files
    \"$0\" simulate static --preset colibri --seed 3 --positions 8 --dwell 1 --units g --gyro -o s.csv --truth t.json
    test \"$(head -n1 s.csv)\" = 't,ax,ay,az,gx,gy,gz'
    test \"$(wc -l < s.csv)\" -eq 3401
    grep -q '\"format\": \"mpcal.imu/1\"' t.json
    grep -q '\"units\": \"g\"' t.json
    \"$0\" simulate static --preset mti-g --positions 2 --dwell 1 --units counts --trials 3 -o s.csv --truth t.json > simulate_static_files.txt
    test -s s_1.csv && test -s s_2.csv && test -s s_3.csv
    test -s t_1.json && test -s t_2.json && test -s t_3.json
    grep -q 'trial 3: s_3.csv, t_3.json' simulate_static_files.txt
    head -n2 s_1.csv | tail -n1 | grep -Eq '^0,[0-9]+,[0-9]+,[0-9]+$'"
    $<TARGET_FILE:mpcal_cli>
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(cli.simulate_static_files PROPERTIES LABELS cli)

# A bias that drifts over the session: the truth file states it, calibrate
# finds it (the drift test) and writes it beside the bias at the end of the session.
add_test(NAME cli.simulate_bias_drift_found
  COMMAND sh -c "set -e; rm -rf drift_files && mkdir drift_files && cd drift_files
    \"$0\" simulate static --preset mti-g --seed 5 --bias-drift 2e-5,-1e-5,3e-5 -o s.csv --truth t.json
    grep -q '\"bias_drift_mps2_per_s\"' t.json
    \"$0\" calibrate s.csv -o c.json > simulate_bias_drift_found.txt 2>&1
    grep -q '^bias drift x, y, z: ' simulate_bias_drift_found.txt
    grep -Fq 'mg/min (p = ' simulate_bias_drift_found.txt
    grep -q '\"bias_drift_mps2_per_s\"' c.json
    grep -q '\"bias_reference_time_s\"' c.json"
    $<TARGET_FILE:mpcal_cli>
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(cli.simulate_bias_drift_found PROPERTIES LABELS cli)
mpcal_cli_test(simulate_bad_bias_drift EXIT 1 MATCH "--bias-drift takes one value or three"
  ABSENT s.csv ARGS simulate static --bias-drift 1e-5,2e-5 -o s.csv)

# At the sensor's pace (`--realtime`, `--speed`): the same log, never ahead
# of its time stamps, and quiet (status 0) when the reader of the pipe quits.
add_test(NAME cli.simulate_realtime
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/simulate_realtime.sh $<TARGET_FILE:mpcal_cli>
          ${CMAKE_CURRENT_BINARY_DIR}/simulate_realtime)
set_tests_properties(cli.simulate_realtime PROPERTIES LABELS cli)
mpcal_cli_test(simulate_realtime_with_trials EXIT 1
  MATCH "^mpcal: error: simulate static: --realtime writes one session; leave out --trials$"
  ABSENT s_1.csv
  ARGS simulate static --realtime --trials 2 -o s.csv)
