"""Subcommands of the ``sectiondeform`` command line, one module each."""
