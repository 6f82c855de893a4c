# SPDX-License-Identifier: MIT
"""The corruptions of the robustness benchmark (sbr_robustness.py): one table, three
severities each, made with albumentations (pinned in tests/python/requirements.txt).

Each entry: its name, what it models, and per severity the albumentations transforms with
their parameters (every random range collapsed to one value, so that a severity is one
level; what stays random - where a shadow, a flare, a rain drop falls, a blur's direction,
the noise - comes from a seed per image, corruption and severity). Severity 2 is at least
as strong as the level of the issue that asked for the benchmark; 1 is milder, 3 stronger.
The table of docs/usage/robustness.md is this one (`sbr_robustness.py --print-table`;
host_robustness_smoke checks that they agree).
"""
import hashlib
import json
import zlib

# name -> (what it models, [severity 1, 2, 3]); a severity is a list of
# (albumentations transform name, keyword arguments), applied in order
TABLE = {
    "under_exposure": ("a dark frame: gamma on [0, 1]", [
        [("RandomGamma", {"gamma_limit": (150, 150)})],
        [("RandomGamma", {"gamma_limit": (200, 200)})],
        [("RandomGamma", {"gamma_limit": (260, 260)})]]),
    "over_exposure": ("a bright frame: brightness added (of the maximum)", [
        [("RandomBrightnessContrast", {"brightness_limit": (0.2, 0.2), "contrast_limit": (0.0, 0.0)})],
        [("RandomBrightnessContrast", {"brightness_limit": (0.3, 0.3), "contrast_limit": (0.0, 0.0)})],
        [("RandomBrightnessContrast", {"brightness_limit": (0.4, 0.4), "contrast_limit": (0.0, 0.0)})]]),
    "low_contrast": ("a flat frame: contrast lowered", [
        [("RandomBrightnessContrast", {"brightness_limit": (0.0, 0.0), "contrast_limit": (-0.35, -0.35)})],
        [("RandomBrightnessContrast", {"brightness_limit": (0.0, 0.0), "contrast_limit": (-0.5, -0.5)})],
        [("RandomBrightnessContrast", {"brightness_limit": (0.0, 0.0), "contrast_limit": (-0.65, -0.65)})]]),
    "backlight": ("against the light: the scene darkened (gamma), a sun flare in the upper 40 %", [
        [("RandomGamma", {"gamma_limit": (140, 140)}),
         ("RandomSunFlare", {"flare_roi": (0.0, 0.0, 1.0, 0.4), "src_radius": 300})],
        [("RandomGamma", {"gamma_limit": (180, 180)}),
         ("RandomSunFlare", {"flare_roi": (0.0, 0.0, 1.0, 0.4), "src_radius": 400})],
        [("RandomGamma", {"gamma_limit": (220, 220)}),
         ("RandomSunFlare", {"flare_roi": (0.0, 0.0, 1.0, 0.4), "src_radius": 500})]]),
    "shadow": ("cast shadows (polygons) anywhere in the frame", [
        [("RandomShadow", {"shadow_roi": (0.0, 0.0, 1.0, 1.0), "num_shadows_limit": (1, 1),
                           "shadow_intensity_range": (0.4, 0.4)})],
        [("RandomShadow", {"shadow_roi": (0.0, 0.0, 1.0, 1.0), "num_shadows_limit": (2, 2),
                           "shadow_intensity_range": (0.5, 0.5)})],
        [("RandomShadow", {"shadow_roi": (0.0, 0.0, 1.0, 1.0), "num_shadows_limit": (3, 3),
                           "shadow_intensity_range": (0.65, 0.65)})]]),
    "motion_blur": ("a moving camera: a line kernel of this length, any direction", [
        [("MotionBlur", {"blur_limit": (5, 5)})],
        [("MotionBlur", {"blur_limit": (9, 9)})],
        [("MotionBlur", {"blur_limit": (15, 15)})]]),
    "defocus": ("out of focus: a disc kernel of this radius", [
        [("Defocus", {"radius": (2, 2), "alias_blur": (0.1, 0.1)})],
        [("Defocus", {"radius": (3, 3), "alias_blur": (0.1, 0.1)})],
        [("Defocus", {"radius": (5, 5), "alias_blur": (0.1, 0.1)})]]),
    "sensor_noise": ("Gaussian noise per pixel and channel, sigma of the maximum", [
        [("GaussNoise", {"std_range": (0.04, 0.04)})],
        [("GaussNoise", {"std_range": (0.06, 0.06)})],
        [("GaussNoise", {"std_range": (0.09, 0.09)})]]),
    "jpeg": ("JPEG compression at this quality", [
        [("ImageCompression", {"quality_range": (25, 25)})],
        [("ImageCompression", {"quality_range": (15, 15)})],
        [("ImageCompression", {"quality_range": (8, 8)})]]),
    "fog": ("haze that lowers contrast and blurs (fog coefficient)", [
        [("RandomFog", {"fog_coef_range": (0.2, 0.2), "alpha_coef": 0.08})],
        [("RandomFog", {"fog_coef_range": (0.3, 0.3), "alpha_coef": 0.08})],
        [("RandomFog", {"fog_coef_range": (0.4, 0.4), "alpha_coef": 0.08})]]),
    "rain": ("rain streaks, the frame dimmed and blurred (albumentations' rain types)", [
        [("RandomRain", {"rain_type": "drizzle"})],
        [("RandomRain", {"rain_type": "heavy"})],
        [("RandomRain", {"rain_type": "torrential"})]]),
}

SEVERITIES = (1, 2, 3)


def names():
    return list(TABLE)


def steps(name, severity):
    """The (transform, kwargs) list of one corruption at one severity (1..3)."""
    return TABLE[name][1][severity - 1]


def key(name, severity, version):
    """A short hash of what makes the pixels: the library's version and the parameters
    (a cache folder's name carries it, so a changed entry is never served from the cache)."""
    blob = json.dumps([version, name, severity, steps(name, severity)], sort_keys=True)
    return hashlib.sha256(blob.encode()).hexdigest()[:10]


def seed(name, severity, image):
    """The seed of one image's corruption: the same pixels on every run."""
    return zlib.crc32(f"{name}:{severity}:{image}".encode()) & 0x7FFFFFFF


def build(name, severity):
    """The albumentations pipeline (every transform always applied)."""
    import albumentations as A
    return A.Compose([getattr(A, t)(p=1.0, **kw) for t, kw in steps(name, severity)])


def _fmt(kw):
    out = []
    for k, v in kw.items():
        if isinstance(v, tuple) and len(v) == 2 and v[0] == v[1]:
            v = v[0]
        out.append(f"{k}={v}")
    return ", ".join(out)


def markdown_table():
    """The table as docs/usage/robustness.md shows it."""
    rows = ["| corruption | what it models | severity 1 | severity 2 | severity 3 |",
            "| --- | --- | --- | --- | --- |"]
    for n, (what, sev) in TABLE.items():
        cells = ["; ".join(f"{t}({_fmt(kw)})" for t, kw in s) for s in sev]
        rows.append(f"| {n} | {what} | " + " | ".join(cells) + " |")
    return "\n".join(rows) + "\n"
