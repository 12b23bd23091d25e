"""What each digit of a frequency costs: FEM error against the exact solution and solve time.

The sweep lives in :mod:`ebantenna.bench.fem_accuracy`, so that ``ebantenna bench`` can gather
it into one report; this script runs it alone. Run: ``python benchmarks/fem_accuracy.py --help``.
"""

from ebantenna.bench.fem_accuracy import main

if __name__ == "__main__":
    main()
