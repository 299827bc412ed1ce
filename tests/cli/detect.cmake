# mpcal detect: the positions of a session and whether they are enough.
set(_xsens ${MPCAL_REAL_DATA}/xsens-multiposition/xsens_acc.mat)
set(_ferraris ${MPCAL_REAL_DATA}/imucal-ferraris/example_ferraris_session.csv)

# Real sessions good enough for their model: exit 0, the table and the verdict.
mpcal_cli_test(detect_xsens_counts EXIT 0
  MATCH "^good enough to calibrate with --model shin-el-sheimy-9"
  ARGS detect ${_xsens} --units counts)
mpcal_cli_test(detect_xsens_positions EXIT 0 MATCH "^  38 static positions; 0 still"
  ARGS detect -v ${_xsens} --units counts)
mpcal_cli_test(detect_xsens_table EXIT 0
  MATCH " 1 +0\\.81 +51\\.66 +50\\.85 +33102\\.2 +33330\\.5 +36433\\.8"
  ARGS detect -v ${_xsens} --units counts)
# By default: the positions and turns in one line, the missing directions,
# the verdict and what to record next; the table of positions only under -v.
add_test(NAME cli.detect_xsens_default_short
  COMMAND sh -c "set -e; \"$0\" detect \"$1\" --gyro-log \"$2\" --units counts --gyro-units counts > detect_xsens_default_short.txt
    grep -q '^38 static positions, 13 of 26 cube directions (missing: -x+y edge, .*), 37 turns$' detect_xsens_default_short.txt
    grep -q '^verdict: usable with warnings$' detect_xsens_default_short.txt
    grep -q '^  next: record 5 more positions' detect_xsens_default_short.txt
    ! grep -q '^  1-2 ' detect_xsens_default_short.txt
    ! grep -q 'quiet level' detect_xsens_default_short.txt
    test $(wc -l < detect_xsens_default_short.txt) -le 10"
  $<TARGET_FILE:mpcal_cli> ${_xsens} ${MPCAL_REAL_DATA}/xsens-multiposition/xsens_gyro.mat)
set_tests_properties(cli.detect_xsens_default_short PROPERTIES LABELS cli
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
mpcal_cli_test(detect_ferraris_six_parameters EXIT 0
  MATCH "verdict: good"
  ARGS detect ${_ferraris} --rate 102.4 --gyro-units dps --model bias-scale-6)
mpcal_cli_test(detect_json EXIT 0 MATCH "wrote positions\\.json"
  ARGS detect ${_xsens} --units counts --json positions.json)

# Not enough: exit 1 and one line saying what to record.
mpcal_cli_test(detect_ferraris_nine_parameters EXIT 1
  MATCH "mpcal: error: the 11 static positions are only 6 distinct orientations, too few to determine the 9 parameters.*--model bias-scale-6"
  ARGS detect ${_ferraris} --rate 102.4 --gyro-units dps)
mpcal_cli_test(detect_too_few_positions EXIT 1
  MATCH "mpcal: error: session has 4 static positions, the 9-parameter model needs at least 10: record 6 more positions, e\\.g\\. with the \\+x face"
  ARGS detect ${MPCAL_TEST_DATA}/detect_four_positions.csv --units g)
mpcal_cli_test(detect_never_still EXIT 1
  MATCH "mpcal: error: .*no static position found in 40\\.0 s.*never stops moving.*--max-still"
  ARGS detect ${MPCAL_TEST_DATA}/detect_always_moving.csv --units g)
mpcal_cli_test(detect_min_static_too_long EXIT 1
  MATCH "mpcal: error: .*longest still stretch lasts 4\\.[0-9]+ s, shorter than the minimum 30 s.*--min-static"
  ARGS detect ${MPCAL_TEST_DATA}/detect_four_positions.csv --units g --min-static 30)

# The units are checked as calibrate checks them, against the gravity given.
mpcal_cli_test(detect_wrong_units EXIT 1
  MATCH "mpcal: error: .*detect_four_positions\\.csv: the readings have a median magnitude of .*look like g: add --units g"
  ARGS detect ${MPCAL_TEST_DATA}/detect_four_positions.csv --units mps2)
mpcal_cli_test(detect_takes_gravity EXIT 0 MATCH "^good enough to calibrate"
  ARGS detect ${_xsens} --units counts --gravity 9.81744)

# Bad input and usage.
mpcal_cli_test(detect_missing_file EXIT 1 MATCH "mpcal: error: .*no_such_log\\.csv"
  ABSENT out.json
  ARGS detect no_such_log.csv --json out.json)
mpcal_cli_test(detect_bad_threshold EXIT 2 MATCH "mpcal: error: .*--threshold"
  ARGS detect ${MPCAL_TEST_DATA}/detect_four_positions.csv --threshold 0.5)
mpcal_cli_test(detect_help EXIT 0 MATCH "mpcal detect xsens_acc.mat --units counts"
  ARGS detect --help)
mpcal_cli_test(detect_gyro_units_dps EXIT 0 MATCH "verdict: good"
  ARGS detect ${_ferraris} --rate 102.4 --model bias-scale-6 --gyro-units dps)
# The Ferraris gyroscope is in deg/s: read as rad/s it is refused, saying so.
mpcal_cli_test(detect_gyro_dps_read_as_rads EXIT 1
  MATCH "mpcal: error: .*example_ferraris_session\\.csv: the gyroscope reaches 895\\.3 rad/s, beyond the 70 rad/s \\(4000 deg/s\\) full scale of MEMS gyroscopes; the readings look like deg/s; give --gyro-units dps"
  ARGS detect ${_ferraris} --rate 102.4)
mpcal_cli_test(detect_gyro_units_unknown EXIT 2
  MATCH "mpcal: error: --gyro-units: 'rpm' is not one of: rads, rad/s, dps, deg/s"
  ARGS detect ${_ferraris} --rate 102.4 --gyro-units rpm)

# With the gyroscope (imu_tk's Xsens recording, raw counts in a file of its
# own): the 37 turns between the 38 positions, in degrees. The nominal scale
# fitted to the tilts agrees with imu_tk's 2.09e-4 rad/s per count, and the
# first turn is a quarter turn about the y axis, as its 90.6 deg tilt says.
set(_xsens_gyro ${MPCAL_REAL_DATA}/xsens-multiposition/xsens_gyro.mat)
mpcal_cli_test(detect_xsens_turns EXIT 0
  MATCH "^  1-2 +51\\.76 +3\\.14 +89\\.[0-9] +-0\\.0[0-9]+ +1\\.000 +0\\.0[0-9]+ +90\\.6"
  ARGS detect -v ${_xsens} --gyro-log ${_xsens_gyro} --units counts --gyro-units counts)
mpcal_cli_test(detect_xsens_turn_count EXIT 0 MATCH "^37-38 "
  ARGS detect -v ${_xsens} --gyro-log ${_xsens_gyro} --units counts --gyro-units counts)
mpcal_cli_test(detect_xsens_turn_scale EXIT 0
  MATCH "nominal scale 0\\.000208[0-9] rad/s per count, fitted to the tilts"
  ARGS detect -v ${_xsens} --gyro-log ${_xsens_gyro} --units counts --gyro-units counts)
# The turns in the JSON report too: 37 of them, the first a quarter turn.
add_test(NAME cli.detect_xsens_turns_json
  COMMAND ${MPCAL_CLI_EXPECT} 0 "^37 89\\.[0-9]"
          --workdir ${CMAKE_CURRENT_BINARY_DIR}/detect_xsens_turns_json
          -- sh -c "\"$0\" detect '${_xsens}' --gyro-log '${_xsens_gyro}' --units counts --gyro-units counts --json p.json >/dev/null && exec ${MPCAL_PYTHON} -c 'import json; t = json.load(open(\"p.json\"))[\"turns\"]; print(len(t), round(t[0][\"angle_deg\"], 1))'"
          $<TARGET_FILE:mpcal_cli>)
set_tests_properties(cli.detect_xsens_turns_json PROPERTIES LABELS cli)
mpcal_cli_test(detect_help_gyro EXIT 0 MATCH "--gyro-log xsens_gyro.mat" ARGS detect --help)
