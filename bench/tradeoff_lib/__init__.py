"""Time against error for one lab's knobs: the modules behind bench/tradeoff.py (docs/tradeoffs.md).

    scenes    reading the repository's scenes and writing their variants (pure: dicts in, dicts out)
    knobs     which configurations each lab sweeps (KNOBS, one function per lab)
    measure   running the lab and the reference tools: frame time, CPU time, error
    results   the Pareto front and the CSV rows
    check     the quick run's checks (CTest tradeoff_quick_*)
    plot      the time-against-error plots (matplotlib)
    heatmaps  the README figures: where the error is
    cli       the command line (bench/tradeoff.py runs it)

The folder is not named bench/tradeoff/: next to bench/tradeoff.py that package would shadow
the script's name on import.
"""
