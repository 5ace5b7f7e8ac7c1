"""Seed statistics for the stress verdicts, standard library only: mean, standard error and the
Student-t quantile (few seeds: the normal quantile would make every tolerance too tight)."""
import math


def mean(xs):
    return sum(xs) / len(xs)


def stderr(xs):
    """Standard error of the mean of xs (0 for a single value: no spread measured)."""
    if len(xs) < 2:
        return 0.0
    m = mean(xs)
    return math.sqrt(sum((x - m) ** 2 for x in xs) / (len(xs) - 1) / len(xs))


def welch_dof(se_a, n_a, se_b, n_b):
    """Welch-Satterthwaite degrees of freedom of a difference of two means with standard errors se_a,
    se_b from n_a, n_b values: near n_a - 1 where b's error is negligible, never below min(n) - 1."""
    lo = min(n_a, n_b) - 1
    num = (se_a ** 2 + se_b ** 2) ** 2
    den = (se_a ** 4 / (n_a - 1) if n_a > 1 else 0.0) + (se_b ** 4 / (n_b - 1) if n_b > 1 else 0.0)
    return max(lo, num / den) if den > 0 else lo


def _t_cdf(x, df):
    """P(T <= x) for x >= 0, by Simpson's rule on the density (smooth; 2000 panels is ample)."""
    c = math.exp(math.lgamma((df + 1) / 2) - math.lgamma(df / 2)) / math.sqrt(df * math.pi)
    f = lambda t: c * (1 + t * t / df) ** (-(df + 1) / 2)  # noqa: E731
    n = 2000
    hstep = x / n
    s = f(0) + f(x) + sum((4 if i % 2 else 2) * f(i * hstep) for i in range(1, n))
    return 0.5 + s * hstep / 3


def t_quantile(p, df):
    """The p-quantile (p > 0.5) of Student's t with df degrees of freedom, by bisection."""
    lo, hi = 0.0, 1.0
    while _t_cdf(hi, df) < p:
        lo, hi = hi, hi * 2
    for _ in range(60):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if _t_cdf(mid, df) < p else (lo, mid)
    return (lo + hi) / 2
