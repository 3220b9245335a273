#!/usr/bin/env python3
"""An independent Hurst estimate of a real elevation model, from its semivariogram.

Written from scratch (plain Python and numpy; tifffile only to read .tif/.tiff) to check
`sylva terrain --analyse MODEL`, sharing no code or constants with it.

usage:
  python3 tools/variogram_fit.py MODEL [--lags A..B] [--spacing METRES] [--json]
                                       [--square] [--detrend] [--table]

  MODEL          an ESRI ASCII grid (.asc), an SRTM tile (.hgt, named like N44W072.hgt)
                 or a GeoTIFF (.tif/.tiff, one band)
  --lags A..B    fit over the integer lags A..B samples (both included) instead of the
                 default window (below)
  --spacing M    metres between samples on both axes, for a file that does not say
                 (a TIFF without ModelPixelScale); overrides the file's spacing
  --json         one JSON object instead of text
  --square       measure only the largest square about the middle (as sylva does)
  --detrend      remove the least-squares plane first
  --table        also print the variogram (lag, metres x/y, gamma x/y, pairs)

Method. The semivariogram gamma(h) = 0.5 * mean((z(x+h) - z(x))^2) is computed along rows
(x, east-west) and along columns (y, north-south) at every integer lag h, over all pairs
whose two ends both have data: a pair with a nodata end is skipped, never filled
(nodata: -9999 and -32768 always; NODATA_value of an .asc header; GDAL_NODATA of a TIFF;
NaN). A fractional-Brownian surface has gamma = c * h^(2H), so H is half the slope of
log gamma against log(lag in metres). Both axes' points go into one least-squares fit
with one slope and an intercept for each axis (so a surface rougher one way than the other
does not tilt the line), each point at its own lag in metres (x and y spacings differ on a geographic grid: degrees are
turned into metres at the grid's middle latitude on the WGS84 ellipsoid, east-west with the
prime-vertical radius times cos(latitude), north-south with the meridian radius). Each
lag's point is weighted 1/h, so every octave of lags weighs the same (unweighted, the many
large integer lags would dominate). Also fitted per axis (H_x, H_y) over the same window.

Default lag window: 3 .. max(8, side // 10) samples, side = the smaller of the grid's two
dimensions.
  * From 3: below about 3 samples a DEM is not the surface but its sensor and resampling
    (SRTM's and NASADEM's resolution is coarser than their posting, and every product is
    interpolated onto its grid), which smooths the first lags and pushes the apparent H up;
    integer metres also add a quantisation floor of 1/12 m^2 that flattens gamma at h = 1
    on gentle ground.
  * To side/10: beyond about a tenth of the side, few independent pairs remain, the ridges
    and valleys the size of the whole map make gamma saturate (bend down), and a regional
    slope adds a term in h^2 (bends it up); both are the finite map, not the roughness.
  * at least 3..8 (a factor 2.7, about 1.4 octaves) so a small grid still has a line.
Real models have no perfectly straight stretch: the local slope of log gamma falls steadily
with the lag (on the SRTM grids local H is 0.83-0.94 between lags 1 and 3, 0.5-0.6 near a
tenth of the side), so H depends on the window: moving its lower end by one sample moves H
by about 0.02-0.04, its upper end from side/10 to side/6 by about 0.03-0.05. Compare
estimates over the same lags (--lags) before blaming the estimator.
R^2 is the weighted coefficient of determination of that line (both axes' intercepts
included in the model).

examples:
  python3 tools/variogram_fit.py terrain/tests/data/dems/pysheds_dem.tif
  python3 tools/variogram_fit.py terrain/tests/data/dems/N44W072.hgt --lags 3..120 --json
  python3 tools/variogram_fit.py plain.tif --spacing 30 --table
"""

import argparse
import json
import math
import os
import re
import struct
import sys

import numpy as np

# Cells with these values have no data, whatever the file says.
ALWAYS_NODATA = (-9999.0, -32768.0)

# WGS84
A_AXIS = 6378137.0
E2 = 6.69437999014e-3


def metres_per_degree(lat_deg):
    """(east-west, north-south) metres per degree at latitude `lat_deg` on WGS84."""
    phi = math.radians(lat_deg)
    w = math.sqrt(1.0 - E2 * math.sin(phi) ** 2)
    prime_vertical = A_AXIS / w
    meridian = A_AXIS * (1.0 - E2) / w ** 3
    return (math.radians(1.0) * prime_vertical * math.cos(phi), math.radians(1.0) * meridian)


class Grid:
    """Heights (float64, NaN = no data, row 0 north), spacing in metres (x, y), and notes."""

    def __init__(self, z, dx, dy, notes):
        self.z = z
        self.dx = dx
        self.dy = dy
        self.notes = notes


def mask_nodata(z, extra=None):
    z = z.astype(np.float64)
    bad = ~np.isfinite(z)
    for v in ALWAYS_NODATA + ((extra,) if extra is not None else ()):
        bad |= z == v
    z[bad] = np.nan
    return z, int(bad.sum())


def read_asc(path):
    header = {}
    with open(path, "r") as f:
        text = f.read()
    tokens = text.split()
    i = 0
    while i + 1 < len(tokens) and re.match(r"^[A-Za-z_]+$", tokens[i]):
        header[tokens[i].lower()] = float(tokens[i + 1])
        i += 2
    ncols, nrows = int(header["ncols"]), int(header["nrows"])
    values = np.array([float(t) for t in tokens[i:i + ncols * nrows]], dtype=np.float64)
    if values.size != ncols * nrows:
        raise SystemExit(f"{path}: {values.size} values for {ncols} x {nrows}")
    z, nodata = mask_nodata(values.reshape(nrows, ncols), header.get("nodata_value"))
    if "cellsize" in header:
        cx = cy = header["cellsize"]
    else:
        cx, cy = header["dx"], header["dy"]
    x0 = header.get("xllcorner", header.get("xllcenter", 0.0))
    y0 = header.get("yllcorner", header.get("yllcenter", 0.0))
    # A geographic grid: corners within longitude/latitude and cells a small fraction of one.
    geographic = abs(x0) <= 360 and abs(y0) <= 90 and cx < 0.1 and cy < 0.1
    notes = {"format": "ESRI ASCII grid", "nodata_value": header.get("nodata_value")}
    if geographic:
        lat = y0 + 0.5 * nrows * cy
        mx, my = metres_per_degree(lat)
        notes.update(geographic=True, latitude=lat, degrees=[cx, cy])
        return Grid(z, cx * mx, cy * my, notes), nodata
    notes.update(geographic=False)
    return Grid(z, cx, cy, notes), nodata


def read_hgt(path):
    size = os.path.getsize(path)
    n = int(round(math.sqrt(size / 2)))
    if n * n * 2 != size:
        raise SystemExit(f"{path}: {size} bytes is not a square of 16-bit samples")
    with open(path, "rb") as f:
        raw = f.read()
    z = np.array(struct.unpack(f">{n * n}h", raw), dtype=np.float64).reshape(n, n)
    z, nodata = mask_nodata(z)
    m = re.match(r"([NS])(\d+)([EW])(\d+)", os.path.basename(path).upper())
    if not m:
        raise SystemExit(f"{path}: name does not say the tile (like N44W072.hgt)")
    south = int(m.group(2)) * (1 if m.group(1) == "N" else -1)
    step = 1.0 / (n - 1)
    mx, my = metres_per_degree(south + 0.5)
    notes = {"format": "SRTM hgt", "geographic": True, "latitude": south + 0.5,
             "degrees": [step, step]}
    return Grid(z, step * mx, step * my, notes), nodata


def read_tif(path):
    import tifffile  # only for TIFF input

    with tifffile.TiffFile(path) as t:
        page = t.pages[0]
        tags = {tag.code: tag.value for tag in page.tags.values()}
        z = page.asarray()
    if z.ndim != 2:
        raise SystemExit(f"{path}: {z.shape}, not one band")
    extra = None
    if 42113 in tags:  # GDAL_NODATA, ASCII
        s = str(tags[42113]).strip().strip("\x00")
        try:
            extra = float(s)
        except ValueError:
            pass
    z, nodata = mask_nodata(z, extra)
    notes = {"format": "TIFF", "gdal_nodata": extra,
             "geo_tags": [n for c, n in ((33550, "ModelPixelScale"), (33922, "ModelTiepoint"),
                                         (34264, "ModelTransformation"),
                                         (34735, "GeoKeyDirectory")) if c in tags]}
    if 33550 not in tags:
        return Grid(z, None, None, notes), nodata
    sx, sy = float(tags[33550][0]), float(tags[33550][1])
    model_type = None
    angular = False
    if 34735 in tags:
        keys = tags[34735]
        for k in range(4, 4 + 4 * int(keys[3]), 4):
            key, loc, _count, value = keys[k:k + 4]
            if key == 1024 and loc == 0:  # GTModelTypeGeoKey: 1 projected, 2 geographic
                model_type = value
    geographic = model_type == 2
    if model_type is None:
        # No keys: guess from the size of the cells, as degrees are tiny.
        angular = sx < 0.1 and sy < 0.1
    if geographic or angular:
        top = float(tags[33922][4]) if 33922 in tags else 45.0
        lat = top - 0.5 * z.shape[0] * sy
        mx, my = metres_per_degree(lat)
        notes.update(geographic=True, latitude=lat, degrees=[sx, sy])
        return Grid(z, sx * mx, sy * my, notes), nodata
    notes.update(geographic=False)
    return Grid(z, sx, sy, notes), nodata


def read(path):
    low = path.lower()
    if low.endswith(".asc"):
        return read_asc(path)
    if low.endswith(".hgt"):
        return read_hgt(path)
    if low.endswith(".tif") or low.endswith(".tiff"):
        return read_tif(path)
    raise SystemExit(f"{path}: not .asc, .hgt, .tif or .tiff")


def detrend(z):
    """z minus its least-squares plane over the cells with data."""
    rows, cols = np.indices(z.shape)
    ok = np.isfinite(z)
    a = np.column_stack([np.ones(ok.sum()), cols[ok], rows[ok]])
    coef, *_ = np.linalg.lstsq(a, z[ok], rcond=None)
    return z - (coef[0] + coef[1] * cols + coef[2] * rows)


def semivariogram(z, max_lag):
    """Per lag 1..max_lag: (gamma along rows, pairs, gamma along columns, pairs)."""
    out = []
    for h in range(1, max_lag + 1):
        row = []
        for d in (z[:, h:] - z[:, :-h], z[h:, :] - z[:-h, :]):
            ok = np.isfinite(d)  # NaN where either end has no data
            n = int(ok.sum())
            row += [0.5 * float(np.mean(d[ok] ** 2)) if n else float("nan"), n]
        out.append(row)
    return out


def fit_axes(xs, ys, ws, axis):
    """Weighted least squares y = a x + b_axis (one slope, an intercept per axis):
    (a, R^2), R^2 of the whole model against the weighted mean."""
    x, y, w, g = (np.asarray(v, dtype=np.float64) for v in (xs, ys, ws, axis))
    w = w / w.sum()
    xc, yc = x.copy(), y.copy()
    for k in np.unique(g):
        m = g == k
        xc[m] -= (w[m] * x[m]).sum() / w[m].sum()
        yc[m] -= (w[m] * y[m]).sum() / w[m].sum()
    a = (w * xc * yc).sum() / (w * xc * xc).sum()
    ss_res = (w * (yc - a * xc) ** 2).sum()
    my = (w * y).sum()
    ss_tot = (w * (y - my) ** 2).sum()
    return a, 1.0 - ss_res / ss_tot if ss_tot > 0 else 1.0


def default_window(side):
    return 3, max(8, side // 10)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("model")
    p.add_argument("--lags", help="A..B, samples")
    p.add_argument("--spacing", type=float, help="metres between samples")
    p.add_argument("--json", action="store_true")
    p.add_argument("--square", action="store_true")
    p.add_argument("--detrend", action="store_true")
    p.add_argument("--table", action="store_true")
    args = p.parse_args()

    grid, nodata = read(args.model)
    if args.spacing:
        grid.dx = grid.dy = args.spacing
    if grid.dx is None:
        raise SystemExit(f"{args.model}: no spacing in the file; give --spacing METRES")
    z = grid.z
    if args.square:
        s = min(z.shape)
        r0, c0 = (z.shape[0] - s) // 2, (z.shape[1] - s) // 2
        z = z[r0:r0 + s, c0:c0 + s]
    if args.detrend:
        z = detrend(z)
    rows, cols = z.shape
    side = min(rows, cols)
    if args.lags:
        m = re.fullmatch(r"(\d+)\.\.(\d+)", args.lags)
        if not m:
            raise SystemExit("--lags A..B, integers")
        lo, hi = int(m.group(1)), int(m.group(2))
    else:
        lo, hi = default_window(side)
    if not 1 <= lo < hi < side:
        raise SystemExit(f"lags {lo}..{hi} do not fit a side of {side}")

    vg = semivariogram(z, hi)
    # One slope, an intercept per axis: an anisotropic surface (rougher one way) has gamma
    # higher along one axis at every lag, which is no reason to bend the common slope.
    xs, ys, ws, axis = [], [], [], []
    for h in range(lo, hi + 1):
        gx, _, gy, _ = vg[h - 1]
        for k, (g, sp) in enumerate(((gx, grid.dx), (gy, grid.dy))):
            if g > 0:
                xs.append(math.log(h * sp)); ys.append(math.log(g)); ws.append(1.0 / h)
                axis.append(k)
    slope, r2 = fit_axes(xs, ys, ws, axis)
    axis = np.asarray(axis)
    hx = fit_axes(np.asarray(xs)[axis == 0], np.asarray(ys)[axis == 0],
                  np.asarray(ws)[axis == 0], axis[axis == 0])[0] / 2
    hy = fit_axes(np.asarray(xs)[axis == 1], np.asarray(ys)[axis == 1],
                  np.asarray(ws)[axis == 1], axis[axis == 1])[0] / 2
    result = {
        "model": args.model,
        "hurst": slope / 2,
        "hurst_x": hx,
        "hurst_y": hy,
        "r2": r2,
        "lags_samples": [lo, hi],
        "lags_metres_x": [lo * grid.dx, hi * grid.dx],
        "lags_metres_y": [lo * grid.dy, hi * grid.dy],
        "spacing_m": [grid.dx, grid.dy],
        "shape": [rows, cols],
        "nodata_cells": nodata,
        "square": args.square,
        "detrend": args.detrend,
        "file": grid.notes,
    }
    if args.table:
        result["variogram"] = [
            {"lag": h, "metres": [h * grid.dx, h * grid.dy], "gamma_x": v[0], "pairs_x": v[1],
             "gamma_y": v[2], "pairs_y": v[3]} for h, v in enumerate(vg, 1)]
    if args.json:
        print(json.dumps(result))
        return
    print(f"{args.model}: {rows} x {cols} samples, spacing {grid.dx:.2f} m (x) "
          f"{grid.dy:.2f} m (y), {nodata} nodata cells"
          + (", central square" if args.square else "") + (", detrended" if args.detrend else ""))
    print(f"H = {slope / 2:.3f}  (H_x {hx:.3f}, H_y {hy:.3f}), R^2 = {r2:.4f}")
    print(f"lags {lo}..{hi} samples = {lo * grid.dx:.0f}..{hi * grid.dx:.0f} m (x), "
          f"{lo * grid.dy:.0f}..{hi * grid.dy:.0f} m (y)")
    if args.table:
        print("lag  metres_x  metres_y  gamma_x  gamma_y  local_H")
        for h, v in enumerate(vg, 1):
            loc = ""
            if h > 1 and vg[h - 2][0] > 0 and v[0] > 0:
                g0 = 0.5 * (vg[h - 2][0] + vg[h - 2][2])
                g1 = 0.5 * (v[0] + v[2])
                loc = f"{0.5 * math.log(g1 / g0) / math.log(h / (h - 1)):.3f}"
            print(f"{h:3d} {h * grid.dx:9.1f} {h * grid.dy:9.1f} {v[0]:9.2f} {v[2]:9.2f}  {loc}")


if __name__ == "__main__":
    sys.exit(main())
