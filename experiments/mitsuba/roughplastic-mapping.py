#!/usr/bin/python3
"""The error of bundlelab's roughplastic mapping (core/scene/MitsubaLoader.cpp, roughPlastic), measured
against Mitsuba 3's roughplastic written out here from its equations (Beckmann D, Smith G1 in its
rational form, dielectric Fresnel at the microfacet, the diffuse base under the *rough* coating's
transmittance in and out and its internal reflectance; linear mode), by quadrature.

For each material: directional albedo of the glossy lobe and of the diffuse base at several incident
angles, Mitsuba against the mapping (Lambert + normalized Phong about the mirror direction, Fresnel
at normal incidence), and the lobe's half-energy cone (the angle from the mirror direction holding
half the lobe's reflected energy at normal incidence).

usage: roughplastic-mapping.py [SCENE.xml] > roughplastic-mapping.md
"""
import math
import sys
import xml.etree.ElementTree as ET

import numpy as np


def fresnel(cos_i, eta):
    """Unpolarized dielectric Fresnel reflectance; eta = n_transmitted / n_incident; cos_i > 0."""
    sin_t2 = (1.0 - cos_i * cos_i) / (eta * eta)
    tir = sin_t2 >= 1.0
    cos_t = np.sqrt(np.maximum(0.0, 1.0 - sin_t2))
    rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t)
    rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t)
    return np.where(tir, 1.0, 0.5 * (rs * rs + rp * rp))


def smith_g1(cos_v, alpha):
    """Beckmann's Smith G1 in Mitsuba's rational approximation (isotropic)."""
    tan_v = np.sqrt(np.maximum(0.0, 1.0 - cos_v * cos_v)) / np.maximum(cos_v, 1e-12)
    a = 1.0 / np.maximum(alpha * tan_v, 1e-12)
    g = (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a)
    return np.where(a >= 1.6, 1.0, g)


def microfacet_grid(alpha, n_t=1200, n_phi=720):
    """Microfacet normals m = (theta_m, phi_m) on a tan(theta_m) grid out to 8 alpha, with weights."""
    t = (np.arange(n_t) + 0.5) / n_t * 8.0 * alpha
    phi = (np.arange(n_phi) + 0.5) / n_phi * 2.0 * math.pi
    T, P = np.meshgrid(t, phi, indexing="ij")
    theta = np.arctan(T)
    # d omega = sin(theta) d theta d phi, d theta = dt / (1 + t^2)
    w = np.sin(theta) / (1.0 + T * T) * (8.0 * alpha / n_t) * (2.0 * math.pi / n_phi)
    m = np.stack([np.sin(theta) * np.cos(P), np.sin(theta) * np.sin(P), np.cos(theta)], axis=-1)
    return m, w, T


def beckmann_d(tan_m, cos_m, alpha):
    return np.exp(-(tan_m * tan_m) / (alpha * alpha)) / (math.pi * alpha * alpha * cos_m ** 4)


def glossy_albedo(theta_i, alpha, eta):
    """Mitsuba's glossy directional albedo: int F D G / (4 cos_i) d omega_o, over microfacet normals
    (d omega_o = 4 (wi.m) d omega_m)."""
    wi = np.array([math.sin(theta_i), 0.0, math.cos(theta_i)])
    m, w, tan_m = microfacet_grid(alpha)
    wi_m = m @ wi
    wo = 2.0 * wi_m[..., None] * m - wi
    ok = (wi_m > 0) & (wo[..., 2] > 0)
    d = beckmann_d(tan_m, m[..., 2], alpha)
    g = smith_g1(np.full_like(wi_m, wi[2]), alpha) * smith_g1(np.clip(wo[..., 2], 1e-12, 1), alpha)
    value = fresnel(np.clip(wi_m, 1e-12, 1), eta) * d * g * wi_m / wi[2]
    return float(np.sum(np.where(ok, value * w, 0.0)))


def rough_transmittance_and_internal(alpha, eta, n=64):
    mus = np.maximum(1e-6, np.arange(n) / (n - 1))
    t_ext = np.array([1.0 - glossy_albedo(math.acos(mu), alpha, eta) for mu in mus])
    r_int = np.array([glossy_albedo(math.acos(mu), alpha, 1.0 / eta) for mu in mus])
    internal = float(np.trapz(r_int * mus, mus) * 2.0)
    return mus, t_ext, internal


def phong_albedo(theta_i, exponent, n_b=4000, n_phi=720):
    """The mapping's lobe (e + 2) / (2 pi) cos^e(r.wo) cos_o over the upper hemisphere (reflectance 1)."""
    r = np.array([-math.sin(theta_i), 0.0, math.cos(theta_i)])  # mirror of wi = (sin, 0, cos)
    beta_max = min(math.pi / 2, 12.0 / math.sqrt(exponent + 1.0))
    b = (np.arange(n_b) + 0.5) / n_b * beta_max
    phi = (np.arange(n_phi) + 0.5) / n_phi * 2.0 * math.pi
    B, P = np.meshgrid(b, phi, indexing="ij")
    # A frame around r: u in the plane of incidence, v = y.
    u = np.array([math.cos(theta_i), 0.0, math.sin(theta_i)])
    cos_o = np.cos(B) * r[2] + np.sin(B) * np.cos(P) * u[2]
    w = np.sin(B) * (beta_max / n_b) * (2.0 * math.pi / n_phi)
    value = (exponent + 2.0) / (2.0 * math.pi) * np.cos(B) ** exponent * cos_o
    return float(np.sum(np.where(cos_o > 0, value * w, 0.0)))


def half_energy_angle_phong(exponent):
    # int_0^b (e+2) cos^(e+1) sin = 1 - cos^(e+2) b  -> half at cos b = 0.5^(1/(e+2))
    return math.degrees(math.acos(0.5 ** (1.0 / (exponent + 2.0))))


def half_energy_angle_beckmann(alpha):
    # At normal incidence wo = reflect about m: the angle to the mirror direction is 2 theta_m; the
    # energy in theta_m < x of D cos_m is 1 - exp(-tan^2 x / alpha^2) (F, G ~ constant near the axis).
    return math.degrees(2.0 * math.atan(alpha * math.sqrt(math.log(2.0))))


def materials(path):
    root = ET.parse(path).getroot()
    out = []
    for b in root.iter("bsdf"):
        if b.get("type") != "roughplastic":
            continue
        p = {c.get("name"): c.get("value") for c in b}
        out.append({
            "alpha": float(p.get("alpha", 0.1)),
            "eta": float(p.get("int_ior", 1.49)) / float(p.get("ext_ior", 1.000277)),
            "diffuse": float(p.get("diffuse_reflectance", "0.5").split()[0]),
        })
    return out


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else "../shared/data/glossy/veach-mis/veach_mis.xml"
    angles = [0, 30, 60, 75, 85]
    print("# roughplastic: Mitsuba 3 against bundlelab's mapping\n")
    print(f"Materials of `{path}`; `experiments/mitsuba/roughplastic-mapping.py` (quadrature, numpy).")
    print("Directional albedo, mapping / Mitsuba, at the incident angles (degrees) in the header;")
    print("diffuse base for the red channel's reflectance. Half-energy cone at normal incidence.\n")
    print("| alpha | eta | exponent | glossy " + " | glossy ".join(f"{a}°" for a in angles) +
          " | diffuse " + " | diffuse ".join(f"{a}°" for a in angles) + " | cone Mitsuba | cone mapping |")
    print("|" + "---|" * (3 + 2 * len(angles) + 2))
    for mat in materials(path):
        alpha, eta, kd = mat["alpha"], mat["eta"], mat["diffuse"]
        f0 = ((eta - 1) / (eta + 1)) ** 2
        exponent = min((2.0 / (alpha * alpha) - 2.0) / 4.0, 1e6)
        # The mapping's base: kd (1 - F0)^2 / (eta^2 (1 - F_int)), F_int of a smooth interface.
        mus = np.linspace(1e-6, 1.0, 4001)
        f_int_smooth = float(np.trapz(fresnel(mus, 1.0 / eta) * mus, mus) * 2.0)
        mapped_base = kd * (1 - f0) ** 2 / (eta * eta * (1 - f_int_smooth))
        grid, t_ext, internal = rough_transmittance_and_internal(alpha, eta)
        diffuse_out = float(np.trapz(np.interp(grid, grid, t_ext) * 2.0 * grid, grid))  # int T(mu) mu dmu * 2
        glossy, diffuse = [], []
        for a in angles:
            th = math.radians(a)
            true_glossy = glossy_albedo(th, alpha, eta)
            mapped_glossy = f0 * phong_albedo(th, exponent)
            glossy.append(mapped_glossy / true_glossy)
            t_i = float(np.interp(math.cos(th), grid, t_ext))
            true_diffuse = kd / (1 - internal) / (eta * eta) * t_i * diffuse_out
            diffuse.append(mapped_base / true_diffuse)
        print(f"| {alpha:g} | {eta:.4g} | {exponent:.6g} | " + " | ".join(f"{g:.3f}" for g in glossy) + " | " +
              " | ".join(f"{d:.3f}" for d in diffuse) +
              f" | {half_energy_angle_beckmann(alpha):.3g}° | {half_energy_angle_phong(exponent):.3g}° |")


if __name__ == "__main__":
    main()
