"""Exercise 4: where does the dominant frequency peak, and how wrong is the two-element model?"""

from scipy.optimize import brentq, minimize_scalar

from ebantenna import Probe
from ebantenna.course import parameters
from ebantenna.fem import Supports, exact_frequencies, modal_analysis

# [data]
STUDENT = None  # a graded variant: the id your teacher gave you, e.g. "s1234"
p = parameters("ex04", student=STUDENT)
probe = Probe(length=p["length_m"])  # the default probe: 40 cm
twin_of = p["twin_of"]  # the contact (fraction of L) whose partner step 3 asks for
# [/data]
L = probe.length


def f_exact(a):
    """Lowest exact frequency (Hz) with the contact at a * L."""
    return exact_frequencies(probe, a * L, n_modes=1)[0]


def f_two_elements(a):
    """Lowest frequency of the paper's two-element model (Hz)."""
    return modal_analysis(probe, Supports(contact=a * L), n_elements=2, n_modes=1).frequencies[0]


peaks = {}
for name, f in (("exact", f_exact), ("two elements", f_two_elements)):
    best = minimize_scalar(lambda a, f=f: -f(a), bounds=(0.5, 0.97), method="bounded",
                           options={"xatol": 1e-6})
    peaks[name] = (best.x, -best.fun)
    print(f"{name:13s}: maximum {-best.fun:7.3f} Hz at {best.x:.4f} L = {100 * best.x * L:.2f} cm")

a_exact, f_max = peaks["exact"]
a_two, _ = peaks["two elements"]
# The exact maximum lies near 80 % of the length, where the paper's data scatter.
assert 0.75 < a_exact < 0.82, a_exact
# It is a maximum: lower on both sides.
assert f_exact(a_exact - 0.05) < f_max and f_exact(a_exact + 0.05) < f_max
# Not monotonic: the same frequency belongs to two contact positions, one on each side.
assert f_exact(twin_of) < f_max and f_exact(0.95) < f_max
# The partner of twin_of: the root of f(a) - f(twin_of L) beyond the maximum. It exists because
# the frequency at the far end of the range is lower still (the root is bracketed).
assert f_exact(0.97) < f_exact(twin_of) < f_max
a_twin = brentq(lambda a: f_exact(a) - f_exact(twin_of), a_exact, 0.97)
print(f"{f_exact(twin_of):.2f} Hz belongs to a contact at {twin_of:.3f} L and at {a_twin:.3f} L")
assert a_twin > a_exact and abs(f_exact(a_twin) - f_exact(twin_of)) < 1e-6
# The two-element model puts the maximum further out, by several per cent of the length.
assert a_two - a_exact > 0.03, (a_two, a_exact)

# The expected answers on the exercise page, checked against these values by the test suite.
# The places are asked in cm from the base: as fractions of L the peaks are the same for every
# length (a uniform beam has no length scale of its own), so they would not tell variants apart.
ANSWERS = {"a_peak_cm": 100 * a_exact * L, "f_peak": f_max,
           "a_peak_two_elements_cm": 100 * a_two * L, "a_twin_cm": 100 * a_twin * L}
# The tolerance of each answer: how far two correct ways of working may differ, and why.
FLAT = ("the maximum is flat: a search on a 1e-3 L grid or a bounded optimiser find it within "
        "1e-3 L (0.045 cm at most)")
TOLERANCES = {
    "a_peak_cm": ("abs", 0.05, FLAT), "a_peak_two_elements_cm": ("abs", 0.05, FLAT),
    "f_peak": ("rel", 1e-4, (
        "at a flat maximum an error of 1e-3 L in the place changes the frequency by far less "
        "than 1e-4"
    )),
    "a_twin_cm": ("abs", 0.05, (
        "any root-finder (or a 1e-3 L grid) on f(a) - f(twin_of L) beyond the maximum"
    )),
}

print("ok: the dominant frequency is not monotonic; two elements misplace its maximum by "
      f"{100 * (a_two - a_exact):.1f} % of the length")
