# export and import: the formats of other tools (the formula tests are
# tests/export/formula_test.py). An mpcal calibration of half the Xsens
# recording (counts, gyroscope with g-sensitivity), the noise of a simulated
# still record, and imu_tk's own calibration of the recording.
set(_half1 ${MPCAL_TEST_DATA}/xsens_imu_half1.json)
set(_noise ${MPCAL_TEST_DATA}/noise_still.json)
set(_imu_tk ${MPCAL_REAL_DATA}/xsens-multiposition/imu_tk)

mpcal_cli_test(export_imu_tk_accel EXIT 0
  MATCH "mpcal: warning: acc\\.calib: imu_tk accelerometer frame: the format's frame is not mpcal's; output corrected by this file is rotated by 0\\.02[0-9]+ rad"
  ARGS export imu-tk-accel ${_half1} -o acc.calib)
mpcal_cli_test(export_imu_tk_gyro_drops_g_sensitivity EXIT 0
  MATCH "mpcal: warning: gyro\\.calib: the format cannot hold the gyroscope's g-sensitivity \\(largest entry 0\\.000[0-9]+ rad/s per m/s\\^2\\); dropped"
  ARGS export imu-tk-gyro ${_half1} -o gyro.calib)
mpcal_cli_test(export_kalibr_intrinsics EXIT 0 MATCH "wrote imu\\.yaml \\(Kalibr imu\\.yaml, model scale-misalignment\\)"
  ARGS export kalibr-scale-misalignment ${_noise} ${_half1} -o imu.yaml)
mpcal_cli_test(export_openvins_bias_warning EXIT 0
  MATCH "mpcal: warning: chain\\.yaml: the format has no key for the gyroscope's bias \\(largest entry [0-9.]+ rad/s\\): written in the file's comments only"
  ARGS export openvins ${_half1} ${_noise} -o chain.yaml)
mpcal_cli_test(export_needs_noise EXIT 1
  MATCH "mpcal: error: format 'openvins' needs a noise file \\(mpcal\\.noise/1\\), and none was given"
  ABSENT chain.yaml
  ARGS export openvins ${_half1} -o chain.yaml)
mpcal_cli_test(export_needs_gyroscope EXIT 1
  MATCH "mpcal: error: format 'imu-tk-gyro' needs the gyroscope's calibration, and '.*apply_calib\\.json' has none"
  ABSENT gyro.calib
  ARGS export imu-tk-gyro ${MPCAL_TEST_DATA}/apply_calib.json -o gyro.calib)
mpcal_cli_test(export_unknown_format EXIT 2 MATCH "FORMAT: 'px5' is not one of: kalibr, "
  ARGS export px5 ${_half1} -o out.txt)
mpcal_cli_test(export_not_an_mpcal_file EXIT 1
  MATCH "mpcal: error: '.*apply_log\\.csv' is not an mpcal JSON file; export takes a calibration file"
  ABSENT out.calib
  ARGS export imu-tk-accel ${MPCAL_TEST_DATA}/apply_log.csv -o out.calib)
mpcal_cli_test(export_two_calibrations EXIT 1 MATCH "are both calibration files" ABSENT out.calib
  ARGS export imu-tk-accel ${_half1} ${MPCAL_TEST_DATA}/xsens_imu_half2.json -o out.calib)
mpcal_cli_test(export_output_is_input EXIT 1 MATCH "mpcal: error: .*"
  ARGS export imu-tk-accel ${_half1} -o ${_half1})

mpcal_cli_test(import_imu_tk_xsens EXIT 0
  MATCH "wrote imu_tk\\.json \\(from imu_tk \\.calib, accelerometer and gyroscope; no 1σ"
  ARGS import imu-tk ${_imu_tk}/xsens_acc.calib ${_imu_tk}/xsens_gyro.calib --units counts
       --gyro-units counts --gravity 9.81744 -o imu_tk.json)
mpcal_cli_test(import_kalibr_camera_chain EXIT 1
  MATCH "mpcal: error: '.*kalibr_camchain\\.yaml' is a camera chain \\(it has 'cam0:'\\), not an IMU file"
  ABSENT out.json
  ARGS import kalibr-scale-misalignment ${MPCAL_TEST_DATA}/export/kalibr_camchain.yaml -o out.json)
mpcal_cli_test(import_imu_tk_short_file EXIT 1
  MATCH "mpcal: error: '.*imu_tk_20_numbers\\.calib' holds 20 numbers; an imu_tk \\.calib holds 21"
  ABSENT out.json
  ARGS import imu-tk ${MPCAL_TEST_DATA}/export/imu_tk_20_numbers.calib --units counts -o out.json)
mpcal_cli_test(import_three_files EXIT 1 MATCH "format 'imu-tk' takes 1 to 2 files \\(ACCEL\\.calib \\[GYRO\\.calib\\]\\), 3 given"
  ABSENT out.json
  ARGS import imu-tk ${_imu_tk}/xsens_acc.calib ${_imu_tk}/xsens_gyro.calib
       ${_imu_tk}/xsens_acc.calib -o out.json)
mpcal_cli_test(import_export_only_format EXIT 2 MATCH "FORMAT: 'imu-tk-accel' is not one of: "
  ARGS import imu-tk-accel ${_imu_tk}/xsens_acc.calib -o out.json)

add_test(NAME cli.export_repeat_imu_tk
  COMMAND sh -c "mkdir -p '${CMAKE_CURRENT_BINARY_DIR}/export_repeat_imu_tk' && cd '${CMAKE_CURRENT_BINARY_DIR}/export_repeat_imu_tk' && exec '${CMAKE_CURRENT_SOURCE_DIR}/export_repeat_imu_tk.sh' \"$0\" '${PROJECT_SOURCE_DIR}'"
          $<TARGET_FILE:mpcal_cli>)
set_tests_properties(cli.export_repeat_imu_tk PROPERTIES LABELS cli)

# A calibration imported from imu_tk (no 1σ): apply and report say so.
set(_imported ${MPCAL_TEST_DATA}/export/imu_tk_imported.json)
mpcal_cli_test(apply_imported_says_no_sigma EXIT 0
  MATCH "calibration imported from imu_tk \\.calib: no 1σ"
  ARGS apply ${_imported} ${MPCAL_REAL_DATA}/xsens-multiposition/xsens_acc.mat
       --columns t=0,ax=1,ay=2,az=3 -o corrected.csv)
mpcal_cli_test(report_imported_says_no_sigma EXIT 0
  MATCH "No 1σ: imported from imu_tk \\.calib, which gives none\\."
  ARGS report --calib ${_imported} -o -)
mpcal_cli_test(export_rate_overrides_the_noise_files EXIT 0 MATCH "update_rate: 200  # Hz$"
  ARGS export kalibr-scale-misalignment ${_half1} ${_noise} --rate 200 -o -)
mpcal_cli_test(export_bad_topic EXIT 1 MATCH "mpcal: error: 'a: b' is not a ROS topic name"
  ABSENT imu.yaml
  ARGS export kalibr-scale-misalignment ${_half1} ${_noise} --rostopic "a: b" -o imu.yaml)
mpcal_cli_test(export_kalibr_noise EXIT 0 MATCH "wrote imu\\.yaml \\(Kalibr imu\\.yaml\\)"
  ARGS export kalibr ${_noise} -o imu.yaml)
mpcal_cli_test(export_no_place_for_noise EXIT 1
  MATCH "mpcal: error: format 'imu-tk-accel' has no place for a noise file \\(mpcal\\.noise/1\\); leave it out"
  ABSENT acc.calib
  ARGS export imu-tk-accel ${_half1} ${_noise} -o acc.calib)
mpcal_cli_test(import_table_says_no_sigma EXIT 0
  MATCH "non-orthogonality zx +-21\\.30[0-9] +no 1σ +mrad"
  ARGS import imu-tk ${_imu_tk}/xsens_acc.calib --units counts --gravity 9.81744 -o acc.json)
mpcal_cli_test(import_counts_read_as_mps2 EXIT 1
  MATCH "mpcal: error: .*is beyond any accelerometer's bias .*; are the tool's raw readings in mps2\\?; give --units counts"
  ABSENT acc.json
  ARGS import imu-tk ${_imu_tk}/xsens_acc.calib -o acc.json)
