# mpcal report: sections from each input, and clear one-line errors that
# leave no report behind. Inputs in tests/data/report/ were written by mpcal
# itself (simulate, calibrate, repeat --json, verify --trajectory-csv walk).
set(_rd ${MPCAL_TEST_DATA}/report)
set(_all --calib ${_rd}/calib.json --session ${_rd}/session.csv
         --repeat ${_rd}/repeat.json --verify ${_rd}/result.json
         --verify-trajectories ${_rd}/walk)
mpcal_cli_test(report.help EXIT 0 MATCH "mpcal report --calib c.json --session s.csv"
  ARGS report --help)
mpcal_cli_test(report.every_section EXIT 0
  MATCH "wrote report.html \\(calibration, session, repeatability, verification\\)"
  ARGS report ${_all} -o report.html)
mpcal_cli_test(report.calibration_only EXIT 0 MATCH "wrote report.html \\(calibration\\)$"
  ARGS report --calib ${_rd}/calib.json -o report.html)
mpcal_cli_test(report.to_stdout EXIT 0 MATCH "^<!DOCTYPE html>"
  ARGS report --verify ${_rd}/result.json -o -)
mpcal_cli_test(report.no_input EXIT 1 MATCH "nothing to report: give at least one of --calib"
  ABSENT report.html ARGS report -o report.html)
mpcal_cli_test(report.no_output EXIT 2 MATCH "--output is required"
  ARGS report --calib ${_rd}/calib.json)
mpcal_cli_test(report.missing_calibration EXIT 1 MATCH "missing\\.json"
  ABSENT report.html ARGS report --calib missing.json -o report.html)
mpcal_cli_test(report.log_as_calibration EXIT 1 MATCH "session\\.csv.*not valid JSON"
  ABSENT report.html ARGS report --calib ${_rd}/session.csv -o report.html)
mpcal_cli_test(report.calibration_as_repeatability EXIT 1
  MATCH "calib\\.json.*mpcal\\.repeatability/1" ABSENT report.html
  ARGS report --repeat ${_rd}/calib.json -o report.html)
mpcal_cli_test(report.repeatability_as_verification EXIT 1
  MATCH "repeat\\.json: format 'mpcal\\.repeatability/1' is not 'mpcal\\.verification/1'"
  ABSENT report.html ARGS report --verify ${_rd}/repeat.json -o report.html)
mpcal_cli_test(report.calibration_as_session EXIT 1 MATCH "calib\\.json:2: .*accelerometer log"
  ABSENT report.html ARGS report --session ${_rd}/calib.json -o report.html)
mpcal_cli_test(report.missing_trajectories EXIT 1 MATCH "nowhere-reference\\.csv: cannot open"
  ABSENT report.html
  ARGS report --verify ${_rd}/result.json --verify-trajectories nowhere -o report.html)
mpcal_cli_test(report.trajectories_without_result EXIT 1
  MATCH "--verify-trajectories needs --verify" ABSENT report.html
  ARGS report --calib ${_rd}/calib.json --verify-trajectories ${_rd}/walk -o report.html)
mpcal_cli_test(report.refuses_to_overwrite_input EXIT 1 MATCH "does not overwrite its input"
  ARGS report --calib ${_rd}/calib.json -o ${_rd}/calib.json)
mpcal_cli_test(report.missing_directory EXIT 1 MATCH "no/such/dir"
  ARGS report --calib ${_rd}/calib.json -o no/such/dir/report.html)
# The summary line and the links at the top name every section written, the
# gyroscope of an IMU calibration and the noise too.
mpcal_cli_test(report.names_gyroscope_and_noise EXIT 0
  MATCH "wrote r\\.html \\(calibration, gyroscope, noise\\)"
  ARGS report --calib ${MPCAL_TEST_DATA}/imu_trial_1.json
       --noise ${MPCAL_TEST_DATA}/noise_still.json -o r.html)
mpcal_cli_test(report.links_gyroscope_and_noise EXIT 0
  MATCH "<nav>Sections: <a href=\"#calibration\">Calibration</a> <a href=\"#gyroscope\">Gyroscope</a> <a href=\"#noise\">Noise</a></nav>"
  ARGS report --calib ${MPCAL_TEST_DATA}/imu_trial_1.json
       --noise ${MPCAL_TEST_DATA}/noise_still.json -o -)
