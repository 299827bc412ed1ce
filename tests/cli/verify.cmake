# mpcal simulate walk and mpcal verify: a simulated walk verified end to end,
# the real RTKLIB walk, and the errors a user meets (one line, no output left).
set(_walk ${CMAKE_CURRENT_BINARY_DIR}/simulate_walk_turn)
set(_real_imu ${MPCAL_REAL_DATA}/rtklib-walk/imu_1730_sf.csv)
set(_real_pos ${MPCAL_REAL_DATA}/rtklib-walk/gnss_1730_sf.pos)
set(_real_columns --columns t=0,ax=1,ay=2,az=3,gx=4,gy=5,gz=6 --units g)

mpcal_cli_test(verify_help EXIT 0 MATCH "mpcal verify --imu walk.csv --gnss ref.pos" ARGS verify --help)
mpcal_cli_test(simulate_walk_help EXIT 0 MATCH "mpcal simulate walk --preset colibri"
  ARGS simulate walk --help)
mpcal_cli_test(simulate_walk_turn EXIT 0
  MATCH "mti-g walk of 1[23][0-9]\\.[0-9] m around a 40 m x 25 m loop.*gyroscope.*turning 90 deg"
  ARGS simulate walk --preset mti-g --seed 5 --turn --rate 200 -o walk.csv --gnss ref.pos
       --truth truth.json)
set_tests_properties(cli.simulate_walk_turn PROPERTIES FIXTURES_SETUP simulated_walk)
# The bias shows in the raw closure (hundreds of metres), the corrected one
# closes within metres.
mpcal_cli_test(verify_simulated_walk EXIT 0
  MATCH "corrected +[0-9]\\.[0-9]{2} "
  ARGS verify --imu ${_walk}/walk.csv --gnss ${_walk}/ref.pos --calib ${_walk}/truth.json
       -o result.json --trajectory-csv walk)
set_tests_properties(cli.verify_simulated_walk PROPERTIES FIXTURES_REQUIRED simulated_walk)
# The default output: the table and a verdict per check; the inputs, the
# clocks and the integration only under -v.
add_test(NAME cli.verify_simulated_walk_verdicts
  COMMAND sh -c "set -e; \"$0\" verify --imu \"$1/walk.csv\" --gnss \"$1/ref.pos\" --calib \"$1/truth.json\" -o verdicts.json > verdicts.txt
    grep -q '^  correction  *good  *the corrected walk is closer to the reference: [0-9.]* m RMS against [0-9.]* m raw' verdicts.txt
    grep -q '^  clock  *good  *the IMU and the reference line up (offset 0.000 s)' verdicts.txt
    grep -q '^  stops  *good  *[0-9]* still stretches with the end rests' verdicts.txt
    grep -q '^  gyroscope  *good  *the gyroscope carried the attitude' verdicts.txt
    ! grep -q '^attitude:' verdicts.txt
    \"$0\" verify -v --imu \"$1/walk.csv\" --gnss \"$1/ref.pos\" -o verdicts.json > verbose.txt
    grep -q '^attitude: levelled at the initial rest' verbose.txt
    grep -q '^  correction  *look at  *no calibration given' verbose.txt"
  $<TARGET_FILE:mpcal_cli> ${_walk})
set_tests_properties(cli.verify_simulated_walk_verdicts PROPERTIES LABELS cli
  FIXTURES_REQUIRED simulated_walk WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
# A walk verified without a calibration says that it judges only the raw walk.
mpcal_cli_test(verify_real_walk_no_calibration EXIT 0
  MATCH "correction +look at +no calibration given"
  ARGS verify --imu ${_real_imu} ${_real_columns} --gnss ${_real_pos} -o result.json)
mpcal_cli_test(verify_real_walk EXIT 0
  MATCH "reference +0\\.19 +128\\.6"
  ARGS verify --imu ${_real_imu} ${_real_columns} --gnss ${_real_pos} -o result.json)
mpcal_cli_test(verify_no_overlap EXIT 1 MATCH "do not overlap in time" ABSENT result.json
  ARGS verify --imu ${_real_imu} ${_real_columns} --gnss ${MPCAL_TEST_DATA}/gnss_enu.csv
       --time-align common -o result.json)
mpcal_cli_test(verify_malformed_reference EXIT 1
  MATCH "gnss_bad_latitude\\.pos:4: latitude is '40\\.09x6916'" ABSENT result.json
  ARGS verify --imu ${_real_imu} ${_real_columns}
       --gnss ${MPCAL_TEST_DATA}/gnss_bad_latitude.pos -o result.json)
mpcal_cli_test(verify_offset_needs_value EXIT 1 MATCH "needs --time-offset" ABSENT result.json
  ARGS verify --imu ${_real_imu} ${_real_columns} --gnss ${_real_pos} --time-align offset
       -o result.json)
mpcal_cli_test(verify_counts EXIT 1 MATCH "raw counts" ABSENT result.json
  ARGS verify --imu ${_real_imu} --columns t=0,ax=1,ay=2,az=3 --units counts
       --gnss ${_real_pos} -o result.json)
mpcal_cli_test(verify_missing_reference EXIT 1 MATCH "no_such.pos: cannot open" ABSENT result.json
  ARGS verify --imu ${_real_imu} --gnss no_such.pos -o result.json)
mpcal_cli_test(verify_bad_mount EXIT 2 MATCH "--mount" ABSENT result.json
  ARGS verify --imu ${_real_imu} --gnss ${_real_pos} --mount sideways -o result.json)
mpcal_cli_test(simulate_walk_too_short EXIT 1 MATCH "too short" ABSENT walk.csv ref.pos
  ARGS simulate walk --length 1 -o walk.csv --gnss ref.pos)
mpcal_cli_test(simulate_walk_same_file EXIT 1 MATCH "same file" ABSENT x.csv
  ARGS simulate walk -o x.csv --gnss x.csv)
mpcal_cli_test(simulate_walk_needs_gnss EXIT 2 MATCH "--gnss" ARGS simulate walk -o walk.csv)
