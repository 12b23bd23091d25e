"""Accuracy against cost of the signal-processing estimators, measured in one run.

The sweep lives in :mod:`ebantenna.bench.signal_accuracy`, so that ``ebantenna bench`` can gather
it into one report; this script runs it alone. Run: ``python benchmarks/signal_accuracy.py --help``.
"""

from ebantenna.bench.signal_accuracy import main

if __name__ == "__main__":
    main()
