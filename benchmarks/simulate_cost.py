"""What each simulated effect costs: seconds per 1000 one-second signals, side by side.

The sweep lives in :mod:`ebantenna.bench.simulate_cost`, so that ``ebantenna bench`` can gather
it into one report; this script runs it alone. Run: ``python benchmarks/simulate_cost.py --help``.
"""

from ebantenna.bench.simulate_cost import main

if __name__ == "__main__":
    main()
