#!/usr/bin/python3
# A still's error against a converged reference that is itself noisy (docs/performance.md, "A
# catalogue still"): the relative RMSE over the objects and the pixels they change, with the
# reference's own noise taken out.
#   /usr/bin/python3 bench/still_error.py REF_A.layers.exr REF_B.layers.exr TEST.layers.exr...
#   /usr/bin/python3 bench/still_error.py --bias REF_A REF_B TEST TEST... (seeds of one setting: bias())
# REF_A and REF_B are renders of the same scene with different seeds (independent samples); the
# reference is their mean R = (A + B) / 2. For a test image X whose noise is independent of theirs,
#   E[Σ (X − R)²] = Σ (X − truth)² + Σ Var(R),   and   E[Σ (A − B)²] = 4 Σ Var(R),
# so the error against the truth is
#   e² = (Σ (X − R)² − Σ (A − B)² / 4) / Σ R²
# (the usual relative RMSE over RGB, sqrt(Σ (x − t)²) / sqrt(Σ t²), of tools/validate/metrics.py).
# The region is insitu tradeoff's (output/composite.h, changed_mask): the objects (coverage > 0.01)
# and the pixels whose luminance R changes from the photo's by more than 3 % over 3 × 3 pixels.
# Prints, per test: the error raw and with the reference's noise out, and the reference's noise.
# Needs numpy and OpenImageIO's Python module (python3-openimageio).
import sys

import numpy as np
import OpenImageIO as oiio

LUMA = np.array([0.2126, 0.7152, 0.0722])


def channels(path, names):
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        sys.exit(f"still_error: {path}: {buf.geterror()}")
    have = list(buf.spec().channelnames)
    missing = [n for n in names if n not in have]
    if missing:
        sys.exit(f"still_error: {path}: no channel {missing[0]} (a layered EXR of insitu render?)")
    return buf.get_pixels(oiio.FLOAT)[:, :, [have.index(n) for n in names]].astype(np.float64)


def box3(img):
    """The mean over the 3 × 3 pixels around each pixel, over those inside the image."""
    pad = np.pad(img, 1)
    ones = np.pad(np.ones_like(img), 1)
    h, w = img.shape
    total = sum(pad[dy:dy + h, dx:dx + w] for dy in range(3) for dx in range(3))
    count = sum(ones[dy:dy + h, dx:dx + w] for dy in range(3) for dx in range(3))
    return total / count


def region(reference, photo, alpha, threshold=0.03):
    diff = box3(np.abs((reference - photo) @ LUMA))
    base = np.maximum(photo @ LUMA, 1e-6)
    return (alpha > 0.01) | (diff > threshold * base)


def references(ref_a, ref_b):
    """The two references A and B, their mean R, the region, Σ R² over it, and R's noise² there."""
    a = channels(ref_a, ['R', 'G', 'B'])
    b = channels(ref_b, ['R', 'G', 'B'])
    if a.shape != b.shape:
        sys.exit(f"still_error: {ref_b}: {b.shape[1]}x{b.shape[0]}, not {ref_a}'s size")
    photo = channels(ref_a, ['photo.R', 'photo.G', 'photo.B'])
    alpha = channels(ref_a, ['objects.A'])[:, :, 0]
    ref = 0.5 * (a + b)
    mask = region(ref, photo, alpha)
    norm = np.sum(ref[mask] ** 2)
    return a, b, ref, mask, norm, np.sum((a - b)[mask] ** 2) / 4 / norm


def test_image(path, shape):
    x = channels(path, ['R', 'G', 'B'])
    if x.shape != shape:
        sys.exit(f"still_error: {path}: {x.shape[1]}x{x.shape[0]}, not the reference's size")
    return x


def errors(ref_a, ref_b, tests):
    """The region's size, the reference's noise, and per test (raw, against the truth or None)."""
    _, _, ref, mask, norm, ref_noise2 = references(ref_a, ref_b)
    out = []
    for path in tests:
        x = test_image(path, ref.shape)
        raw2 = np.sum((x - ref)[mask] ** 2) / norm
        err2 = raw2 - ref_noise2
        out.append((np.sqrt(raw2), np.sqrt(err2) if err2 > 0 else None))
    return int(mask.sum()), mask.size, np.sqrt(ref_noise2), out


def bias(ref_a, ref_b, tests):
    """The tests' common bias against the truth over the region, relative to its RMS, and the noise
    of one test. The tests are K ≥ 2 renders of one setting with different seeds, X̄ their mean and
    s² = Σ_k (X_k − X̄)² / (K − 1) per pixel. Against the truth t, X̄ − t = b + (noise of variance
    s²/K), and R's noise is independent of both, so
        b² = (Σ (X̄ − R)² − Σ s² / K − Σ (A − B)² / 4) / Σ R²,    noise² of one = Σ s² / Σ R².
    Also b²'s standard error, from the spread of its per-pixel terms."""
    a, b, ref, mask, norm, ref_noise2 = references(ref_a, ref_b)
    xs = np.stack([test_image(path, ref.shape)[mask] for path in tests])
    k = len(xs)
    mean = xs.mean(0)
    s2 = np.sum((xs - mean) ** 2, 0) / (k - 1)
    # Per pixel and channel: its term of b² · Σ R². The terms' spread gives b²'s standard error
    # as if the pixels were independent (the references' are; a denoised image's are not, so
    # this understates it).
    terms = (mean - ref[mask]) ** 2 - s2 / k - (a - b)[mask] ** 2 / 4
    b2 = np.sum(terms) / norm
    se_b2 = np.sqrt(terms.size * np.var(terms)) / norm
    return b2, se_b2, np.sqrt(np.sum(s2) / norm), np.sqrt(ref_noise2)


def main():
    if len(sys.argv) > 1 and sys.argv[1] == '--bias':
        if len(sys.argv) < 6:
            sys.exit("usage: still_error.py --bias REF_A REF_B TEST TEST...")
        b2, se, noise, ref_noise = bias(sys.argv[2], sys.argv[3], sys.argv[4:])
        root = lambda v: f"{100 * np.sqrt(v):.2f} %" if v > 0 else "0"
        print(f"bias {root(b2)} (b² = {1e4 * b2:.3f} ± {1e4 * se:.3f} %²; b² + 2σ: "
              f"{root(b2 + 2 * se)}), noise of one test {100 * noise:.2f} %, reference noise {100 * ref_noise:.2f} %")
        return
    if len(sys.argv) < 4:
        sys.exit("usage: still_error.py REF_A REF_B TEST...")
    count, size, noise, out = errors(sys.argv[1], sys.argv[2], sys.argv[3:])
    print(f"region: {count} of {size} pixels; reference noise {100 * noise:.3f} %")
    for path, (raw, err) in zip(sys.argv[3:], out):
        against = f"{100 * err:.3f} %" if err is not None else "below the reference's noise"
        print(f"{path}: {100 * raw:.3f} % raw, {against} against the truth")


if __name__ == '__main__':
    main()
