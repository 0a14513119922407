"""The augmented Lagrangian around a Newton solve (Uzawa): while a contact's
largest penetration exceeds its gap tolerance, set its multipliers to the
current pressures and solve again from the converged state."""

#: reason of a step whose penetration stayed above the gap tolerance
AUGMENTATION_LIMIT = "AUGMENTATION_LIMIT"


def augment_until_within(contacts, prepare, solve, log):
    """Augment the augmented-Lagrangian ``contacts`` of a converged solve, at
    most max(max_augmentations) times. ``prepare()`` evaluates every contact
    at the current state; ``solve()`` is one Newton solve (converged,
    iterations, norms, reason). Returns (converged, extra iterations,
    augmentations, norms, reason); ``norms`` and ``reason`` are None when no
    solve was needed."""
    augmented = [c for c in contacts if c.augmented]
    count, extra, norms, reason = 0, 0, None, None
    if not augmented:
        return True, 0, 0, norms, reason
    limit = max(c.enforcement.max_augmentations for c in augmented)
    while True:
        prepare()
        over = [c for c in augmented if c.max_penetration() > c.enforcement.gap_tolerance]
        if not over:
            return True, extra, count, norms, reason
        if count >= limit:
            worst = max(over, key=lambda c: c.max_penetration() / c.enforcement.gap_tolerance)
            log(f"   augmented Lagrangian: contact {worst.name!r} still penetrates {worst.max_penetration():.3g} "
                f"> gap_tolerance {worst.enforcement.gap_tolerance:.3g} after {count} augmentations "
                "(raise max_augmentations or eps_n)")
            return False, extra, count, norms, AUGMENTATION_LIMIT
        for c in augmented:
            c.augment()
        count += 1
        ok, its, norms, reason = solve()
        extra += its
        if not ok:
            return False, extra, count, norms, reason
