"""Draws Documentation/images/mirror-frames.png: each quadric mirror type's meridian (the x-z plane
of its mirror frame) with its default numbers, the physical part (z_range) in bold, the foci, and
the camera centre that the default mirror_to_camera gives. Run from the repository root:

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Documentation/mirror-frames.py
"""
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import catadioptricar as car  # noqa: E402


def defaults(kind):
    camera = car.vtkCatadioptricCamera()
    assert camera.SetMirrorType(kind), camera.GetLastError()
    values = {}
    for key in camera.GetMirrorParameterKeys(kind):
        values[key] = camera.GetMirrorParameter(key)
    return values


def camera_in_mirror_frame(h):
    """The camera centre (camera-frame origin) in the mirror frame: -R^T t."""
    r = np.array(h).reshape(4, 4)[:3, :3]
    t = np.array(h).reshape(4, 4)[:3, 3]
    return -r.T @ t


def meridian(kind, p, z):
    """x >= 0 of the surface at height z (NaN where there is none)."""
    with np.errstate(invalid="ignore"):
        if kind == "hyperboloid":
            a, b = p["a"][0], p["b"][0]
            return b * np.sqrt(z * z / (a * a) - 1.0)
        if kind == "paraboloid":
            f = p["focal"][0]
            return np.sqrt(4.0 * f * (z + f))
        if kind == "ellipsoid":
            ax, _, az = p["semi_axes"]
            return ax * np.sqrt(1.0 - z * z / (az * az))
        if kind == "cone":
            return math.tan(math.radians(p["half_angle"][0])) * np.abs(z)
        if kind == "quadric":  # the default: x^2 + y^2 + z^2 + Omega_33 = 0
            r2 = -p["matrix"][15]
            return np.sqrt(r2 - z * z)
    raise ValueError(kind)


def foci(kind, p):
    if kind == "hyperboloid":
        c = math.hypot(p["a"][0], p["b"][0])
        return [c, -c]
    if kind == "paraboloid":
        return [0.0]
    return []


kinds = ["hyperboloid", "paraboloid", "ellipsoid", "cone", "quadric"]
fig, axes = plt.subplots(1, len(kinds), figsize=(3.2 * len(kinds), 4.2))
for ax, kind in zip(axes, kinds):
    p = defaults(kind)
    zmin, zmax = p["z_range"]
    cam = camera_in_mirror_frame(p["mirror_to_camera"])
    lo = min(cam[2], zmin) - 0.01
    hi = max(zmax, 0.0) + 0.02
    z = np.linspace(lo, hi, 800)
    x = meridian(kind, p, z)
    for sign in (1, -1):
        ax.plot(sign * x, z, color="0.75", lw=1)
        part = (z >= zmin) & (z <= zmax)
        ax.plot(np.where(part, sign * x, np.nan), z, color="tab:blue", lw=3)
    ax.axhspan(zmin, zmax, color="tab:blue", alpha=0.07)
    ax.axvline(0.0, color="0.5", lw=0.6, ls="--")
    ax.arrow(0, 0, 0.015, 0, head_width=0.002, color="tab:red", length_includes_head=True)
    ax.arrow(0, 0, 0, 0.015, head_width=0.002, color="tab:green", length_includes_head=True)
    ax.text(0.016, -0.004, "x", color="tab:red")
    ax.text(0.002, 0.016, "z", color="tab:green")
    for f in foci(kind, p):
        ax.plot([0], [f], "k+", ms=8)
    ax.plot([cam[0]], [cam[2]], "ks", ms=6)
    ax.text(cam[0] + 0.003, cam[2], "camera", va="center", fontsize=8)
    ax.set_title(kind, fontsize=10)
    ax.set_aspect("equal")
    ax.set_xlim(-0.09, 0.09)
    ax.set_ylim(lo, hi)
    ax.tick_params(labelsize=7)
fig.suptitle("Mirror frames (metres): the physical mirror (z_range) in blue, foci +, the camera "
             "centre of the default mirror_to_camera", fontsize=9)
fig.tight_layout()
fig.savefig("Documentation/images/mirror-frames.png", dpi=90)
print("wrote Documentation/images/mirror-frames.png")
