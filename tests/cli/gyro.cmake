# The gyroscope: calibrate of a whole IMU (imu_tk's Xsens recording, two
# files of raw counts merged by row), the simulator's gyroscope, apply's
# gyroscope units.
set(_xsens_acc ${MPCAL_REAL_DATA}/xsens-multiposition/xsens_acc.mat)
set(_xsens_gyro ${MPCAL_REAL_DATA}/xsens-multiposition/xsens_gyro.mat)

mpcal_cli_test(calibrate_xsens_imu EXIT 0
  MATCH "gyroscope: 37 turns between the positions; converged after [0-9]+ iterations; gravity carried over each turn vs measured after it, tilt RMS [0-9.]+ deg before \\(nominal scale, bias at every position\\), 0\\.(0|1|2|30|31|32)[0-9]* deg after"
  ARGS calibrate ${_xsens_acc} --gyro-log ${_xsens_gyro} --units counts --gyro-units counts
       --gravity 9.81744 -o imu.json)
mpcal_cli_test(calibrate_xsens_imu_writes_imu_file EXIT 0 MATCH "wrote imu.json"
  ARGS calibrate ${_xsens_acc} --gyro-log ${_xsens_gyro} --units counts --gyro-units counts
       --gravity 9.81744 -o imu.json)
mpcal_cli_test(calibrate_gyro_log_rows_differ EXIT 1
  MATCH "mpcal: error: .*apply_log.csv has [0-9]+ rows but .*xsens_acc.mat has 51175" ABSENT imu.json
  ARGS calibrate ${_xsens_acc} --gyro-log ${MPCAL_TEST_DATA}/apply_log.csv --units counts
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
