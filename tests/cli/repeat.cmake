# mpcal repeat: the paper's trials (tests/data/paper/) give the paper's table.
set(_paper ${MPCAL_TEST_DATA}/paper)
set(_colibri ${_paper}/colibri_trial1.json ${_paper}/colibri_trial2.json
             ${_paper}/colibri_trial3.json)
set(_mtig ${_paper}/mtig_trial1.json ${_paper}/mtig_trial2.json ${_paper}/mtig_trial3.json)
set(_row "( +-?[0-9.]+){4} +")  # unit, 3 trials and the mean, then std (n)

mpcal_cli_test(repeat.help EXIT 0 MATCH "mpcal repeat monday.csv" ARGS repeat --help)
# Table 4: population std of Colibri bias x, y (paper: 8e-3, 7.7e-2 g), and
# the sample std beside it.
mpcal_cli_test(repeat.paper_colibri_bias_x EXIT 0
  MATCH "bias x +mg${_row}7\\.994 +9\\.791 " ARGS repeat ${_colibri})
mpcal_cli_test(repeat.paper_colibri_bias_y EXIT 0
  MATCH "bias y +mg${_row}76\\.92 " ARGS repeat ${_colibri})
# Table 6: MTi-G bias x, y, z (paper: 7.4e-3, 1.7e-3, 1.6e-2 g).
mpcal_cli_test(repeat.paper_mtig_bias_x EXIT 0
  MATCH "bias x +mg${_row}7\\.473 " ARGS repeat ${_mtig})
mpcal_cli_test(repeat.paper_mtig_bias_y EXIT 0
  MATCH "bias y +mg${_row}1\\.772 " ARGS repeat ${_mtig})
mpcal_cli_test(repeat.paper_mtig_bias_z EXIT 0
  MATCH "bias z +mg${_row}16\\.36 " ARGS repeat ${_mtig})
# Where the paper's printed deviation does not follow from its trials: the
# trials give 164.6 mg (printed 0.16432 g) and 0.5793 ppm (printed 0.61 ppm).
mpcal_cli_test(repeat.paper_colibri_bias_z_computed EXIT 0
  MATCH "bias z +mg${_row}164\\.6 " ARGS repeat ${_colibri})
mpcal_cli_test(repeat.paper_colibri_scale_x_computed EXIT 0
  MATCH "scale error x +ppm${_row}0\\.5793 " ARGS repeat ${_colibri})
# The paper gives no per-trial 1σ: no verdict, said so.
mpcal_cli_test(repeat.paper_no_verdict EXIT 0
  MATCH "No verdict on any parameter: no uncertainty given" ARGS repeat ${_mtig})
mpcal_cli_test(repeat.writes_json_and_csv EXIT 0 MATCH "wrote t\\.json.*wrote t\\.csv|wrote t\\.csv"
  ARGS repeat ${_mtig} --json t.json --csv t.csv)
mpcal_cli_test(repeat.two_trials EXIT 0 MATCH "std \\(n-1\\)"
  ARGS repeat ${_paper}/mtig_trial1.json ${_paper}/mtig_trial2.json)

# Errors: one line, exit 1 (2 for usage), no output file.
mpcal_cli_test(repeat.one_session EXIT 1 MATCH "at least 2 sessions.*got 1" ABSENT t.json
  ARGS repeat ${_paper}/mtig_trial1.json --json t.json)
mpcal_cli_test(repeat.refuses_other_gravity EXIT 1
  MATCH "trial 2 \\(.*gravity_9\\.78\\.json\\) was calibrated against gravity 9\\.78" ABSENT t.json
  ARGS repeat ${_paper}/colibri_trial1.json ${_paper}/colibri_trial1_gravity_9.78.json
       --json t.json)
mpcal_cli_test(repeat.missing_session EXIT 1 MATCH "no_such_session\\.csv" ABSENT t.csv
  ARGS repeat ${_paper}/mtig_trial1.json no_such_session.csv --csv t.csv)
mpcal_cli_test(repeat.not_a_calibration EXIT 1 MATCH "README\\.md:[0-9]+: "
  ARGS repeat ${_paper}/mtig_trial1.json ${_paper}/README.md)
mpcal_cli_test(repeat.bad_significance EXIT 2 MATCH "significance"
  ARGS repeat ${_mtig} --significance 2)
mpcal_cli_test(repeat.no_arguments EXIT 2 MATCH "SESSION_OR_CALIB" ARGS repeat)
mpcal_cli_test(repeat.json_and_csv_same_file EXIT 1
  MATCH "--json and --csv both name 'table': one would overwrite the other" ABSENT table
  ARGS repeat ${_colibri} --json table --csv ./table)
# The last line: whether one calibration serves every session.
mpcal_cli_test(repeat_verdict_one_calibration_good EXIT 0
  MATCH "^verdict: good: one calibration serves every session$"
  ARGS repeat ${MPCAL_TEST_DATA}/imu_trial_1.json ${MPCAL_TEST_DATA}/imu_trial_2.json)
mpcal_cli_test(repeat_verdict_no_sigma_look_at EXIT 0
  MATCH "^verdict: look at: no 1σ to judge the sessions by$"
  ARGS repeat ${_colibri})
