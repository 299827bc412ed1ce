# The shell itself: help, usage errors, unknown subcommands.
mpcal_cli_test(help EXIT 0 MATCH "calibrate" ARGS --help)
mpcal_cli_test(version EXIT 0 MATCH "^mpcal [0-9]+\\.[0-9]+\\.[0-9]+" ARGS --version)
mpcal_cli_test(no_subcommand EXIT 2
  MATCH "mpcal: error: no subcommand given: one of calibrate, detect, apply" ARGS)
mpcal_cli_test(no_subcommand_prints_help EXIT 2 MATCH "^Subcommands:" ARGS)
mpcal_cli_test(unknown_subcommand EXIT 2
  MATCH "mpcal: error: 'frobnicate' is not an mpcal subcommand; the subcommands are calibrate, detect"
  ARGS frobnicate)
