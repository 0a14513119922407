"""The Uzawa loop of solve/augmented.py with stand-in contacts: no mesh, no
solver. A stand-in's penetration halves at each augmentation, as a stiff
penalty's would shrink."""
from hypercontact.solve.augmented import AUGMENTATION_LIMIT, augment_until_within


class Enforcement:
    def __init__(self, tol, limit):
        self.gap_tolerance, self.max_augmentations = tol, limit


class HalvingContact:
    augmented = True
    name = "stand-in"

    def __init__(self, penetration, tol, limit):
        self.penetration, self.enforcement, self.augments = penetration, Enforcement(tol, limit), 0

    def max_penetration(self):
        return self.penetration

    def augment(self):
        self.augments += 1
        self.penetration *= 0.5


def solve_ok():
    return True, 3, [1.0, 1e-9], "CONVERGED"


def test_augments_until_the_penetration_is_within_the_tolerance():
    c = HalvingContact(1.0, 0.1, 30)  # 1 → 0.5 → 0.25 → 0.125 → 0.0625: four augmentations
    ok, extra, count, norms, reason = augment_until_within([c], lambda: None, solve_ok, print)
    assert ok and count == 4 and c.augments == 4 and extra == 4 * 3 and reason == "CONVERGED"


def test_stops_at_the_limit_naming_the_contact():
    c, said = HalvingContact(1.0, 1e-6, 2), []
    ok, extra, count, norms, reason = augment_until_within([c], lambda: None, solve_ok, said.append)
    assert not ok and count == 2 and reason == AUGMENTATION_LIMIT
    assert "stand-in" in said[0] and "max_augmentations" in said[0]


def test_penalty_contacts_and_a_failed_solve():
    class Penalty(HalvingContact):
        augmented = False

    ok, extra, count, norms, reason = augment_until_within([Penalty(1.0, 0.1, 5)], lambda: None, solve_ok, print)
    assert ok and count == 0 and norms is None  # nothing to augment: no solve
    c = HalvingContact(1.0, 0.1, 5)
    ok, extra, count, norms, reason = augment_until_within(
        [c], lambda: None, lambda: (False, 7, [1.0, 2.0], "DIVERGED_MAX_IT"), print)
    assert not ok and count == 1 and extra == 7 and reason == "DIVERGED_MAX_IT"
