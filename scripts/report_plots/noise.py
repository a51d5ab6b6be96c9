"""The run's own noise, and the one rule by which the summary ranks anything.

`deepgi report --repeats R` renders every row R times, each repeat with the
temporal sequence started at another point and the per-pixel rotation hash
seeded with the repeat's index (another realisation of every pixel's
rotation, the per-pixel field included). For a quantity the summary compares (a column averaged
over scenes, layers, tap counts ...), `per_repeat` gives its value in each
repeat; the quantity's run-to-run spread is the range (largest minus
smallest) of those values.

The rule (`decide`): two values differ only when their means differ by more
than the larger of their two spreads. A candidate whose mean lies within
that noise of the lowest mean is tied with it; a lowest is named only when
every other candidate lies beyond it. The rule is pairwise, so a sentence
comparing two patterns and one ranking all of them never disagree. With one
repeat the noise is not measured, and nothing is ranked.
"""
import math


def _finite(values):
    return [v for v in values if v is not None and math.isfinite(v)]


def spread(values):
    """Range of a quantity's per-repeat values; None with fewer than two."""
    values = _finite(values)
    if len(values) < 2:
        return None
    return max(values) - min(values)


class Decision:
    """What may be said of a comparison.

    means: name -> mean over repeats; noise: the largest noise of a pair
    with the lowest (each pair's the larger of its two spreads; None when a
    candidate has fewer than two repeats); lowest: the name of the lowest
    mean when it is beyond the noise of every other, else None; tied: the
    names within the noise of the lowest mean (the lowest first), empty when
    the noise is unknown; reason: why nothing is named, or ""."""

    def __init__(self, means, noise, lowest, tied, reason):
        self.means = means
        self.noise = noise
        self.lowest = lowest
        self.tied = tied
        self.reason = reason

    @property
    def resolved(self):
        return self.lowest is not None


def decide(candidates):
    """candidates: name -> list of the quantity's per-repeat values (in
    any order; None or non-finite values are left out). Returns a Decision."""
    values = {name: _finite(v) for name, v in candidates.items()}
    values = {name: v for name, v in values.items() if v}
    means = {name: sum(v) / len(v) for name, v in values.items()}
    if len(means) < 2:
        return Decision(means, None, None, [], "fewer than two candidates were measured")
    spreads = {name: spread(v) for name, v in values.items()}
    if any(s is None for s in spreads.values()):
        return Decision(means, None, None, [],
                        "each configuration was rendered once, so the run did not measure "
                        "its noise")
    order = sorted(means, key=lambda name: means[name])
    lowest = order[0]
    pair_noise = {name: max(spreads[lowest], spreads[name]) for name in order[1:]}
    tied = [lowest] + [name for name in order[1:]
                       if means[name] - means[lowest] <= pair_noise[name]]
    # The noise stated: of the tied pairs when some are tied, else of the
    # pair with the runner-up.
    noise = max(pair_noise[name] for name in (tied[1:] or order[1:2]))
    if len(tied) == 1:
        return Decision(means, noise, lowest, tied, "")
    return Decision(means, noise, None, tied,
                    "the differences are within the run-to-run spread")

