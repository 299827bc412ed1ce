# The gyroscope: calibrate of a whole IMU (imu_tk's Xsens recording, two
# files of raw counts merged by row), the simulator's gyroscope, apply's
# gyroscope units.
set(_xsens_acc ${MPCAL_REAL_DATA}/xsens-multiposition/xsens_acc.mat)
set(_xsens_gyro ${MPCAL_REAL_DATA}/xsens-multiposition/xsens_gyro.mat)

mpcal_cli_test(calibrate_xsens_imu EXIT 0
  MATCH "gyroscope: 37 turns between the positions; converged after [0-9]+ iterations; gravity carried over each turn vs measured after it, tilt RMS [0-9.]+ deg before \\(nominal scale, bias at every position\\), 0\\.(0|1|2|30|31|32)[0-9]* deg after"
  ARGS calibrate -v ${_xsens_acc} --gyro-log ${_xsens_gyro} --units counts --gyro-units counts
       --gravity 9.81744 -o imu.json)
mpcal_cli_test(calibrate_xsens_imu_writes_imu_file EXIT 0 MATCH "wrote imu.json"
  ARGS calibrate ${_xsens_acc} --gyro-log ${_xsens_gyro} --units counts --gyro-units counts
       --gravity 9.81744 -o imu.json)
# A gyroscope log of another session, 4.8 s long: the overlap is too short to
# calibrate, and the warning says why.
mpcal_cli_test(calibrate_gyro_log_much_shorter EXIT 1
  MATCH "mpcal: error: .*xsens_acc.mat: session has 1 static position.*xsens_acc\\.mat spans 0\\.030 to 511\\.718 s but .*apply_log\\.csv spans 0\\.000 to 4\\.780 s: one stream is much shorter" ABSENT imu.json
  ARGS calibrate ${_xsens_acc} --gyro-log ${MPCAL_TEST_DATA}/apply_log.csv
       --gyro-columns t=time,gx=acc_x,gy=acc_y,gz=acc_z --units counts
       --gyro-units counts --gravity 9.81744 -o imu.json)
mpcal_cli_test(calibrate_help_gyro EXIT 0 MATCH "--gyro-log xsens_gyro.mat"
  ARGS calibrate --help)
mpcal_cli_test(calibrate_unknown_gyro_units EXIT 2
  MATCH "--gyro-units: 'rpm' is not one of: rads, rad/s, dps, deg/s, counts" ABSENT imu.json
  ARGS calibrate ${_xsens_acc} --gyro-units rpm -o imu.json)
mpcal_cli_test(simulate_gyro_counts EXIT 0 MATCH "with gyroscope \\(counts\\)"
  ARGS simulate static --preset colibri --gyro --gyro-units counts --positions 12 --dwell 3
       -o s.csv --truth t.json)
mpcal_cli_test(apply_unknown_out_gyro_units EXIT 2
  MATCH "--out-gyro-units: 'rpm' is not one of: rads, dps"
  ARGS apply ${MPCAL_TEST_DATA}/apply_calib.json ${MPCAL_TEST_DATA}/apply_log.csv -o out.csv
       --out-gyro-units rpm)
# demo: the gyroscope of the simulated session beside the accelerometer,
# against its truth and the Cramér-Rao bound of the turns.
mpcal_cli_test(demo_gyroscope EXIT 0
  MATCH "^RMS of \\(estimate - truth\\) / Cramér-Rao bound over the 9 entries of the gyroscope's M: (0|1)\\.[0-9]+"
  ARGS demo --output-dir out)
mpcal_cli_test(demo_gyroscope_turns EXIT 0
  MATCH "^gyroscope: 26 turns between the positions; converged after [0-9]+ iterations"
  ARGS demo -v --output-dir out)
mpcal_cli_test(demo_gyroscope_verdict EXIT 0
  MATCH "^  gyroscope +good +26 turns fit to 0\\.[0-9]+ deg RMS"
  ARGS demo --output-dir out)
# repeat and report over IMU files (two calibrations of simulated colibri
# sessions with --gyro, seeds 1 and 2, made by mpcal calibrate).
set(_imu1 ${MPCAL_TEST_DATA}/imu_trial_1.json)
set(_imu2 ${MPCAL_TEST_DATA}/imu_trial_2.json)
mpcal_cli_test(repeat_imu_files EXIT 0 MATCH "^gyroscope over 2 trials \\(ω = M \\(raw − b\\)\\):"
  ARGS repeat ${_imu1} ${_imu2})
mpcal_cli_test(repeat_imu_files_scale_row EXIT 0
  MATCH "^scale-factor error x +ppm +-?[0-9.]+ ± [0-9.]+ +-?[0-9.]+ ± [0-9.]+ +-?[0-9.]+ +[0-9.]+  (consistent|changed) \\(p = "
  ARGS repeat ${_imu1} ${_imu2})
mpcal_cli_test(report_imu_gyro_section EXIT 0 MATCH "<section id=.gyroscope.>"
  ARGS report --calib ${_imu1} -o -)
# Two halves by time of the Xsens recording (rows 1-25587 and the rest, each
# calibrated by mpcal calibrate --gyro-units counts): each half found its own
# nominal rad/s per count (0.5 % apart), and M is relative to it. Compared at
# one nominal scale the halves agree; compared as written, every scale and
# bias would read "changed".
set(_half1 ${MPCAL_TEST_DATA}/xsens_imu_half1.json)
set(_half2 ${MPCAL_TEST_DATA}/xsens_imu_half2.json)
mpcal_cli_test(repeat_imu_counts_at_one_nominal_scale EXIT 0
  MATCH "^\\(raw counts: every trial at trial 1's nominal 0\\.000209[0-9]* rad/s per count"
  ARGS repeat ${_half1} ${_half2})
mpcal_cli_test(repeat_imu_counts_halves_agree EXIT 0
  MATCH "^gyroscope: every entry consistent between the trials within their 1σ"
  ARGS repeat ${_half1} ${_half2})
# The gyroscope's units from calibrate to apply: for each unit of its
# columns, in the log and in a file of its own, the log corrected with the
# calibration matches the true rates within the calibration's 1σ.
foreach(_units rads dps counts)
  foreach(_placement same own)
    set(_name gyro_units_round_trip_${_units}_${_placement})
    add_test(NAME cli.${_name}
      COMMAND sh -c "mkdir -p '${CMAKE_CURRENT_BINARY_DIR}/${_name}' && cd '${CMAKE_CURRENT_BINARY_DIR}/${_name}' && exec '${CMAKE_CURRENT_SOURCE_DIR}/gyro_units_round_trip.sh' \"$0\" ${_units} ${_placement}"
              $<TARGET_FILE:mpcal_cli>)
    set_tests_properties(cli.${_name} PROPERTIES LABELS cli)
  endforeach()
endforeach()
# A log in deg/s read as rad/s whose rates stay under the 70 rad/s check (the
# simulated session played 8 times slower: 59 deg/s at most): the turns do
# not determine M at the estimate, calibrate says "gyroscope not calibrated",
# and the file agrees: no gyroscope block, the reason among its warnings;
# apply then leaves the gyroscope columns as they are.
add_test(NAME cli.gyro_not_calibrated_is_not_written
  COMMAND ${MPCAL_CLI_EXPECT} 0 "^ok$"
          --workdir ${CMAKE_CURRENT_BINARY_DIR}/gyro_not_calibrated_is_not_written
          -- sh -c "set -e
    \"$0\" simulate static --preset colibri --gyro --seed 2 --turn 16 -o sim.csv >/dev/null
    awk -F, 'BEGIN { OFS = \",\"; OFMT = CONVFMT = \"%.17g\"; k = 45 / atan2(1, 1) / 8 } NR == 1 { print; next } { $1 *= 8; $5 *= k; $6 *= k; $7 *= k; print }' sim.csv > dps.csv
    \"$0\" calibrate dps.csv -o c.json > out.txt 2>&1
    grep -q 'gyroscope not calibrated' out.txt
    grep -q '\"format\": \"mpcal.accelerometer/1\"' c.json
    ! grep -q '\"gyroscope\": {' c.json
    grep -q '\"gyroscope not calibrated' c.json
    \"$0\" apply c.json dps.csv -o out.csv > apply.txt
    ! grep -q gyroscope apply.txt
    cut -d, -f5-7 dps.csv > raw.txt; cut -d, -f5-7 out.csv > applied.txt; cmp -s raw.txt applied.txt
    echo ok"
  $<TARGET_FILE:mpcal_cli>)
set_tests_properties(cli.gyro_not_calibrated_is_not_written PROPERTIES LABELS cli)
# An IMU file whose block says rad/s though its provenance read the log in
# deg/s (the block then holds no units of the log): apply refuses it unless
# --gyro-units says what the log to correct is in.
add_test(NAME cli.apply_imu_units_contradict_provenance
  COMMAND ${MPCAL_CLI_EXPECT} 1 "the gyroscope block is for logs in rad/s, but the file was calibrated from a log in deg/s \\('--gyro-units dps' in its provenance\\); calibrate again, or give --gyro-units"
          --absent out.csv
          --workdir ${CMAKE_CURRENT_BINARY_DIR}/apply_imu_units_contradict_provenance
          -- sh -c "sed 's/--gyro-units rads/--gyro-units dps/' '${_imu1}' > c.json && \"$0\" simulate static --preset colibri --gyro --seed 1 --positions 12 --dwell 3 -o s.csv > /dev/null && exec \"$0\" apply c.json s.csv -o out.csv"
          $<TARGET_FILE:mpcal_cli>)
set_tests_properties(cli.apply_imu_units_contradict_provenance PROPERTIES LABELS cli)
add_test(NAME cli.apply_imu_units_given_on_the_command_line_win
  COMMAND ${MPCAL_CLI_EXPECT} 0 "warning: the log's gyroscope was read in dps as --gyro-units says; the gyroscope of 'c.json' is for logs in rads"
          --workdir ${CMAKE_CURRENT_BINARY_DIR}/apply_imu_units_given_on_the_command_line_win
          -- sh -c "sed 's/--gyro-units rads/--gyro-units dps/' '${_imu1}' > c.json && \"$0\" simulate static --preset colibri --gyro --seed 1 --positions 12 --dwell 3 -o s.csv > /dev/null && exec \"$0\" apply c.json s.csv --gyro-units dps -o out.csv"
          $<TARGET_FILE:mpcal_cli>)
set_tests_properties(cli.apply_imu_units_given_on_the_command_line_win PROPERTIES LABELS cli)
# The IMU files written before the block recorded the log's units are read as
# they were: rad/s (imu_trial_1.json) and counts (xsens_imu_half1.json).
add_test(NAME cli.apply_imu_file_in_rads_reads_as_before
  COMMAND ${MPCAL_CLI_EXPECT} 0 "gyroscope in rad/s;"
          --workdir ${CMAKE_CURRENT_BINARY_DIR}/apply_imu_file_in_rads_reads_as_before
          -- sh -c "\"$0\" simulate static --preset colibri --gyro --seed 1 --positions 12 --dwell 3 -o s.csv > /dev/null && exec \"$0\" apply '${_imu1}' s.csv -o out.csv"
          $<TARGET_FILE:mpcal_cli>)
set_tests_properties(cli.apply_imu_file_in_rads_reads_as_before PROPERTIES LABELS cli)
# An IMU file out of the plausible ranges (plausible.h) is refused, naming
# the field: M's diagonal of 1e308 would be applied as it is.
add_test(NAME cli.apply_imu_m_beyond_plausible
  COMMAND ${MPCAL_CLI_EXPECT} 1 "'gyroscope.m\\[0\\]' = 1e\\+308 is not a scale 1 \\+ s with \\|s\\| < 0.5"
          --absent out.csv
          --workdir ${CMAKE_CURRENT_BINARY_DIR}/apply_imu_m_beyond_plausible
          -- sh -c "awk '/\"m\": \\[/ && !done { print; getline; print \"      1e308,\"; done = 1; next } { print }' '${_imu1}' > c.json && \"$0\" simulate static --preset colibri --gyro --seed 1 --positions 12 --dwell 3 -o s.csv > /dev/null && exec \"$0\" apply c.json s.csv -o out.csv"
          $<TARGET_FILE:mpcal_cli>)
set_tests_properties(cli.apply_imu_m_beyond_plausible PROPERTIES LABELS cli)
# repeat and report read the same file the same way (a scale-factor error of
# -1e9 ppm was shown as a trial's).
foreach(_cmd "repeat c.json '${_imu2}'" "report --calib c.json -o -")
  string(REGEX MATCH "^[a-z]+" _verb "${_cmd}")
  add_test(NAME cli.${_verb}_imu_m_beyond_plausible
    COMMAND ${MPCAL_CLI_EXPECT} 1 "'gyroscope.m\\[4\\]' = -1000 is not a scale 1 \\+ s"
            --workdir ${CMAKE_CURRENT_BINARY_DIR}/${_verb}_imu_m_beyond_plausible
            -- sh -c "awk '/\"m\": \\[/ && !done { print; getline; print; getline; print; getline; print; getline; print; getline; print \"      -1000,\"; done = 1; next } { print }' '${_imu1}' > c.json && exec \"$0\" ${_cmd}"
            $<TARGET_FILE:mpcal_cli>)
  set_tests_properties(cli.${_verb}_imu_m_beyond_plausible PROPERTIES LABELS cli)
endforeach()

# --gyro-log: one flag, one check, in every command that takes it.
foreach(_cmd detect calibrate)
  add_test(NAME cli.${_cmd}_gyro_log_empty_name
    COMMAND ${MPCAL_CLI_EXPECT} 2 "--gyro-log: the file name is empty; give a path"
            --workdir ${CMAKE_CURRENT_BINARY_DIR}/${_cmd}_gyro_log_empty_name
            -- sh -c "exec \"$0\" ${_cmd} '${_xsens_acc}' --gyro-log '' --units counts --gyro-units counts"
            $<TARGET_FILE:mpcal_cli>)
  set_tests_properties(cli.${_cmd}_gyro_log_empty_name PROPERTIES LABELS cli)
  mpcal_cli_test(${_cmd}_gyro_log_missing EXIT 1
    MATCH "mpcal: error: .*no_such_gyro.mat"
    ARGS ${_cmd} ${_xsens_acc} --gyro-log no_such_gyro.mat --units counts --gyro-units counts)
  mpcal_cli_test(${_cmd}_gyro_columns_without_gyro_log EXIT 2 MATCH "--gyro-columns requires --gyro-log"
    ARGS ${_cmd} ${_xsens_acc} --gyro-columns t=0,gx=1,gy=2,gz=3 --units counts)
endforeach()
# A gyroscope log's header (t,gx,gy,gz; time,wx,wy,wz), and --gyro-columns
# when the header does not say.
foreach(_case "t,gx,gy,gz" "time,wx,wy,wz" "t,gyr_x,gyr_y,gyr_z")
  string(REPLACE "," "_" _tag "${_case}")
  add_test(NAME cli.calibrate_gyro_log_header_${_tag}
    COMMAND ${MPCAL_CLI_EXPECT} 0 "gyroscope: 37 turns between the positions; converged"
            --workdir ${CMAKE_CURRENT_BINARY_DIR}/calibrate_gyro_log_header_${_tag}
            -- sh -c "{ echo '${_case}'; awk '{ print $1 \",\" $2 \",\" $3 \",\" $4 }' '${_xsens_gyro}'; } > g.csv && exec \"$0\" calibrate -v '${_xsens_acc}' --gyro-log g.csv --units counts --gyro-units counts --gravity 9.81744"
            $<TARGET_FILE:mpcal_cli>)
  set_tests_properties(cli.calibrate_gyro_log_header_${_tag} PROPERTIES LABELS cli)
endforeach()
add_test(NAME cli.calibrate_gyro_log_header_unknown_names
  COMMAND ${MPCAL_CLI_EXPECT} 1 "g.csv:1: the header names no gyroscope columns \\(found: clock, a, b, c\\); expected gx/gyr_x/wx/x \\(and y, z\\), or a mapping of the columns.*--gyro-columns t=NAME,gx=NAME,gy=NAME,gz=NAME"
          --workdir ${CMAKE_CURRENT_BINARY_DIR}/calibrate_gyro_log_header_unknown_names
          -- sh -c "{ echo 'clock,a,b,c'; awk '{ print $1 \",\" $2 \",\" $3 \",\" $4 }' '${_xsens_gyro}'; } > g.csv && exec \"$0\" calibrate '${_xsens_acc}' --gyro-log g.csv --units counts --gyro-units counts --gravity 9.81744"
          $<TARGET_FILE:mpcal_cli>)
set_tests_properties(cli.calibrate_gyro_log_header_unknown_names PROPERTIES LABELS cli)
add_test(NAME cli.calibrate_gyro_columns_map_the_gyro_log
  COMMAND ${MPCAL_CLI_EXPECT} 0 "gyroscope: 37 turns between the positions; converged"
          --workdir ${CMAKE_CURRENT_BINARY_DIR}/calibrate_gyro_columns_map_the_gyro_log
          -- sh -c "{ echo 'clock,a,b,c'; awk '{ print $1 \",\" $2 \",\" $3 \",\" $4 }' '${_xsens_gyro}'; } > g.csv && exec \"$0\" calibrate -v '${_xsens_acc}' --gyro-log g.csv --gyro-columns t=clock,gx=a,gy=b,gz=c --units counts --gyro-units counts --gravity 9.81744"
          $<TARGET_FILE:mpcal_cli>)
set_tests_properties(cli.calibrate_gyro_columns_map_the_gyro_log PROPERTIES LABELS cli)
mpcal_cli_test(calibrate_gyro_columns_take_gyroscope_keys EXIT 1
  MATCH "key 'ax' is not a gyroscope's \\(known: t, gx, gy, gz\\)"
  ARGS calibrate ${_xsens_acc} --gyro-log ${_xsens_gyro} --gyro-columns t=0,ax=1,gy=2,gz=3
       --units counts --gyro-units counts)
