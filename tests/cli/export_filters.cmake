# mpcal export for the filters' noise files and the autopilots' parameters,
# and mpcal import of the autopilots' parameters: the files written, the
# values not measured warned about, bad input refused with one line.
set(_noise_json ${MPCAL_TEST_DATA}/noise_still.json)

mpcal_cli_test(export_orb_slam3 EXIT 0 MATCH "wrote orb\\.yaml \\(ORB-SLAM3 settings"
  ARGS export orb-slam3 ${_noise_json} -o orb.yaml)
mpcal_cli_test(export_vins_warns_bound EXIT 0
  MATCH "mpcal: warning: vins\\.yaml: acc_w was not measured; the file has its upper bound"
  ARGS export vins ${_noise_json} -o vins.yaml)
mpcal_cli_test(export_kf_gins_scale_not_measured EXIT 0
  MATCH "kf\\.yaml: gsstd was not measured"
  ARGS export kf-gins ${_noise_json} -o kf.yaml)
mpcal_cli_test(export_ros_imu_stdout EXIT 0
  MATCH "linear_acceleration_covariance: .[0-9.e-]+, 0\\.0, 0\\.0"
  ARGS export ros-imu ${_noise_json} -o -)
mpcal_cli_test(export_orb_slam3_takes_noise EXIT 1
  MATCH "mpcal: error: format 'orb-slam3' has no place for a calibration file"
  ABSENT orb.yaml ARGS export orb-slam3 ${MPCAL_TEST_DATA}/apply_calib.json -o orb.yaml)

# The autopilots: a calibration in m/s², its dropped angles said.
mpcal_cli_test(export_px4 EXIT 0
  MATCH "px4\\.params: the format cannot hold non_orthogonality"
  ARGS export px4 ${MPCAL_TEST_DATA}/apply_calib.json -o px4.params)
mpcal_cli_test(export_ardupilot EXIT 0 MATCH "wrote ap\\.param \\(ArduPilot parameters"
  ARGS export ardupilot ${MPCAL_TEST_DATA}/apply_calib.json -o ap.param)
mpcal_cli_test(export_px4_counts_refused EXIT 1
  MATCH "mpcal: error: .*raw counts.*driver's m/s\\^2" ABSENT px4.params
  ARGS export px4 ${MPCAL_TEST_DATA}/xsens_imu_half1.json -o px4.params)
# Written, read back and applied: the autopilot's own formula on the raw
# rows gives what `mpcal apply` of the imported calibration gives.
add_test(NAME cli.autopilot_formula
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/autopilot_formula.sh $<TARGET_FILE:mpcal_cli>
          ${MPCAL_TEST_DATA}/apply_calib.json ${MPCAL_TEST_DATA}/apply_log.csv)
set_tests_properties(cli.autopilot_formula PROPERTIES LABELS cli
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
# Import, then export: the parameter lines come back as they were.
add_test(NAME cli.import_ardupilot_round_trip
  COMMAND sh -c "set -e
    \"$0\" export ardupilot \"$1\" -o ap.param > /dev/null 2>&1
    \"$0\" import ardupilot ap.param -o imported.json > /dev/null
    \"$0\" export ardupilot imported.json -o again.param > /dev/null
    grep -v '^#' ap.param > a.txt; grep -v '^#' again.param > b.txt; cmp a.txt b.txt"
  $<TARGET_FILE:mpcal_cli> ${MPCAL_TEST_DATA}/apply_calib.json)
set_tests_properties(cli.import_ardupilot_round_trip PROPERTIES LABELS cli
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
mpcal_cli_test(import_px4_camera_chain EXIT 1
  MATCH "mpcal: error: .*line 1: not a QGroundControl parameter line" ABSENT c.json
  ARGS import px4 ${MPCAL_TEST_DATA}/export/kalibr_camchain.yaml -o c.json)
