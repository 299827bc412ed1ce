# The shell itself: help, usage errors, unknown subcommands.
mpcal_cli_test(help EXIT 0 MATCH "calibrate" ARGS --help)
mpcal_cli_test(version EXIT 0 MATCH "^mpcal [0-9]+\\.[0-9]+\\.[0-9]+" ARGS --version)
mpcal_cli_test(no_subcommand EXIT 2 MATCH "mpcal: error: .*subcommand" ARGS)
mpcal_cli_test(unknown_subcommand EXIT 2 MATCH "mpcal: error: " ARGS frobnicate)
