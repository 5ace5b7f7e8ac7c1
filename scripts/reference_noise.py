"""Equal-time ratios with the reference's own noise taken off (standard library only: the GPU kit
carries this file beside scripts/device-bench-summary.py).

A reference R is itself a Monte Carlo image (the path tracer at spp samples, its own seed). Against R,
a method's measured relMSE is in expectation its own relMSE plus R's relative noise n_R (their
errors are independent; the runner's `reference_noise_relmse`, the variance of R's pixel means
weighed as relMSE weighs errors). Where the path tracer takes several times R's samples in the
same time, n_R is most of its measured relMSE and a measured ratio understates the gap. The
corrected ratio takes n_R off the method's relMSE and divides by the path tracer's own relMSE,
predicted as n_R * spp / its samples: the same estimator, its variance falling as 1/samples.
"""
import json
import os


def reference_spp(task_dir):
    """The spp of the reference a `bundlelab run` task was judged against: the `spp` of the JSON
    the runner writes beside the reference image named in the task's reference.txt; None where
    either is missing (a reference given as a file has no JSON)."""
    try:
        with open(os.path.join(task_dir, "reference.txt")) as f:
            image = os.path.join(task_dir, f.read().strip())
        with open(os.path.splitext(image)[0] + ".json") as f:
            spp = json.load(f).get("spp")
        return int(spp) if spp else None
    except (OSError, ValueError, TypeError):
        return None


def predicted_own_relmse(noise, spp, samples):
    """The path tracer's own relMSE after `samples` samples, from its reference's noise at `spp`;
    None where a figure is missing or zero (a reference of unknown noise)."""
    if not noise or not spp or not samples or noise <= 0:
        return None
    return noise * spp / samples


def noise_corrected(relmse, noise, tracer_noise, spp, tracer_samples):
    """(relmse - noise) over the path tracer's predicted own relMSE; None where any is missing. It
    goes negative where the method's relMSE is within the reference's noise: read it as parity."""
    predicted = predicted_own_relmse(tracer_noise, spp, tracer_samples)
    if relmse is None or noise is None or predicted is None:
        return None
    return (relmse - noise) / predicted
