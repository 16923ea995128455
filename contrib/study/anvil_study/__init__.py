"""anvil's study tool: ladders, references, work-precision tables and plots,
stability maps and physics cost (doc/study.md). Run by `anvil --study FILE`
or the `anvil-study` script the build writes next to the executable."""
