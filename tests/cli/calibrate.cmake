# mpcal calibrate and mpcal demo: the main job, on the real recordings, and
# its refusals (one line, exit 1 or 2, no calibration file left behind).
set(_xsens ${MPCAL_REAL_DATA}/xsens-multiposition/xsens_acc.mat)
set(_ferraris ${MPCAL_REAL_DATA}/imucal-ferraris/example_ferraris_session.csv)

mpcal_cli_test(calibrate_help EXIT 0 MATCH "mpcal calibrate session.csv -o calib.json"
  ARGS calibrate --help)
mpcal_cli_test(calibrate_xsens_counts EXIT 0
  MATCH "^static positions: 38 used"
  ARGS calibrate -v ${_xsens} --units counts --gravity 9.81744 -o calib.json)
# The split-half check on the real recording: both splits possible, the
# halves consistent, and stored in the file.
mpcal_cli_test(calibrate_xsens_split_half EXIT 0
  MATCH "split-half \\(by time, 19 \\+ 19 positions\\): RMS z [0-9.]+ \\(honest 1σ: 1 ± 0.24\\); consistent"
  ARGS calibrate -v ${_xsens} --units counts --gravity 9.81744 -o calib.json)
mpcal_cli_test(calibrate_ferraris_split_half_not_possible EXIT 0
  MATCH "split-half \\(by time, 5 \\+ 5 positions\\): not possible"
  ARGS calibrate -v ${_ferraris} --rate 102.4 --gyro-units dps --model bias-scale-6 -o calib.json)
# A bumped stretch: 4 mg on x from 246 s to 400 s of a 40-position session.
# The halves by time disagree; calibrate says so, at the split's share of the
# check's 1 %, widens every 1σ, and stores the widening in the file.
add_test(NAME cli.calibrate_bumped_stretch_widens
  COMMAND sh -c "set -e; rm -rf bumped && mkdir bumped && cd bumped
    \"$0\" simulate static --preset mti-g --seed 3 --positions 40 -o s.csv
    awk -F, 'NR == 1 { print; next } { if ($1 > 246 && $1 < 400) $2 += 0.004; print $1 \",\" $2 \",\" $3 \",\" $4 }' s.csv > bumped.csv
    \"$0\" calibrate -v bumped.csv -o c.json > out.txt 2>&1
    grep -q 'split-half (by time, 21 + 20 positions): RMS z [0-9.]* (honest 1σ: 1 ± 0.24); the halves DISAGREE beyond chance (chi-square p = .* < 0.005, the check.s 0.01 shared by 2 splits)' out.txt
    grep -q '^every 1σ above is widened by [2-9]' out.txt
    grep -q 'every 1σ is widened by' out.txt
    grep -q '\"widening\": [2-9]' c.json
    \"$0\" calibrate bumped.csv > default.txt 2>&1
    grep -q '^  split-half  *do not use  *the halves of the session disagree (p = .* < 0.005)' default.txt"
  $<TARGET_FILE:mpcal_cli>)
set_tests_properties(cli.calibrate_bumped_stretch_widens PROPERTIES LABELS cli)
# The default output: the table, one verdict line per check, the file; the
# diagnostics behind the checks only under -v.
add_test(NAME cli.calibrate_xsens_default_verdicts
  COMMAND sh -c "set -e; \"$0\" calibrate \"$1\" --units counts --gravity 9.81744 > calibrate_xsens_default_verdicts.txt
    test $(wc -l < calibrate_xsens_default_verdicts.txt) -le 25
    grep -q '^  fit  *good  *residuals as the sensor noise explains (variance factor 0\\.[0-9]*)' calibrate_xsens_default_verdicts.txt
    grep -q '^  positions  *good  *38 positions determine every parameter' calibrate_xsens_default_verdicts.txt
    grep -q '^  bias drift  *good  *the bias is constant over the session (p = 0\\.' calibrate_xsens_default_verdicts.txt
    grep -q '^  split-half  *good  *the two halves of the session agree' calibrate_xsens_default_verdicts.txt
    grep -q '^  units  *good  *raw counts, 1 g = 40[0-9][0-9]\\.[0-9]* counts' calibrate_xsens_default_verdicts.txt
    ! grep -q 'split-half (by time' calibrate_xsens_default_verdicts.txt
    ! grep -q 'variance factor .* (1 = residuals' calibrate_xsens_default_verdicts.txt"
  $<TARGET_FILE:mpcal_cli> ${_xsens})
set_tests_properties(cli.calibrate_xsens_default_verdicts PROPERTIES LABELS cli
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
mpcal_cli_test(calibrate_xsens_verbose_split_half_z EXIT 0
  MATCH "^  z: bias x [+-][0-9.]+, bias y [+-][0-9.]+, .*θzy [+-][0-9.]+$"
  ARGS calibrate -v ${_xsens} --units counts --gravity 9.81744)
add_test(NAME cli.calibrate_colour_on_terminal_only
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/colour.sh $<TARGET_FILE:mpcal_cli> ${_xsens}
          --units counts --gravity 9.81744)
set_tests_properties(cli.calibrate_colour_on_terminal_only PROPERTIES LABELS cli)
mpcal_cli_test(calibrate_xsens_read_as_mps2 EXIT 1
  MATCH "look like raw ADC counts: add --units counts" ABSENT calib.json
  ARGS calibrate ${_xsens} --gravity 9.81744 -o calib.json)
mpcal_cli_test(calibrate_ferraris_six_parameters EXIT 0
  MATCH "^fit: converged after"
  ARGS calibrate -v ${_ferraris} --rate 102.4 --gyro-units dps --model bias-scale-6 -o calib.json)
mpcal_cli_test(calibrate_ferraris_nine_parameters_refused EXIT 1
  MATCH "do not determine theta.*--model bias-scale-6" ABSENT calib.json
  ARGS calibrate ${_ferraris} --rate 102.4 --gyro-units dps -o calib.json)
mpcal_cli_test(calibrate_missing_file EXIT 1 MATCH "no_such.csv" ABSENT calib.json
  ARGS calibrate no_such.csv -o calib.json)
mpcal_cli_test(calibrate_output_directory_missing EXIT 1
  MATCH "mpcal: error: cannot write 'no/such/dir/calib.json': directory 'no/such/dir' does not exist; create it"
  ARGS calibrate ${_xsens} --units counts --gravity 9.81744 -o no/such/dir/calib.json)
mpcal_cli_test(calibrate_output_is_input EXIT 1 MATCH "xsens_acc.mat"
  ARGS calibrate ${_xsens} --units counts -o ${_xsens})
mpcal_cli_test(calibrate_unknown_model EXIT 2
  MATCH "--model: 'twelve' is not one of: shin-el-sheimy-9, bias-scale-6" ABSENT calib.json
  ARGS calibrate ${_xsens} --model twelve -o calib.json)
mpcal_cli_test(calibrate_xsens_robust_cauchy EXIT 0 MATCH "^fit: converged after"
  ARGS calibrate -v ${_xsens} --units counts --gravity 9.81744 --robust cauchy -o calib.json)
mpcal_cli_test(calibrate_unknown_robust_loss EXIT 2
  MATCH "--robust: 'tukey' is not one of: none, huber, cauchy" ABSENT calib.json
  ARGS calibrate ${_xsens} --units counts --robust tukey -o calib.json)
mpcal_cli_test(calibrate_gravity_and_latitude EXIT 2 MATCH "excludes" ABSENT calib.json
  ARGS calibrate ${_xsens} --gravity 9.81 --latitude 45 -o calib.json)
mpcal_cli_test(calibrate_latitude_out_of_range EXIT 2 MATCH "--latitude" ABSENT calib.json
  ARGS calibrate ${_xsens} --latitude 95 -o calib.json)

mpcal_cli_test(demo EXIT 0
  MATCH "^RMS of \\(estimate - truth\\) / Cramér-Rao bound over the 9 parameters: [0-9.]+"
  ARGS demo --output-dir out)
# The rest of the workflow on the same device (its report: report.render.demo).
mpcal_cli_test(demo_repeatability EXIT 0
  MATCH "^bias x, y, z changed between sessions beyond their 1σ"
  ARGS demo --output-dir out)
mpcal_cli_test(demo_verification EXIT 0
  MATCH "^Walked loop against GNSS: the end lands [0-9.]+ m from the start with raw readings, [0-9]\\.[0-9]+ m corrected"
  ARGS demo --output-dir out)
