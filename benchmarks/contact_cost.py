"""What the strike's Hertz contact costs against the contact linearised at the preload.

The sweep lives in :mod:`ebantenna.bench.contact_cost`, so that ``ebantenna bench`` can gather
it into one report; this script runs it alone. Run: ``python benchmarks/contact_cost.py --help``.
"""

from ebantenna.bench.contact_cost import main

if __name__ == "__main__":
    main()
