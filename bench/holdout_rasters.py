#!/usr/bin/python3
"""Hold-out accuracy of gridding methods on rasters, five kinds of sampling (bench/RESULTS.md).

For each terrain (a raster of the shared data) and each kind of sampling (random 2,000; random 8,000;
survey lines: 2,000 samples on 5 straight tracks at random bearings, none between them; 12 clusters;
2,000 at random around a hole a quarter of the terrain across), the samples are raster nodes, taken
out, and up to 20,000 of the other nodes inside the samples' convex hull are the truth. Every method
makes its surface over the same box in the terrain's UTM frame, a net of 65 x 65 nodes (129 x 129 for
8,000 samples); each surface is read bilinearly at the truth (relief's net, the others' grids at a
quarter of its spacing): RMSE in metres.

Methods: gdal_grid -a linear and -a invdist; GRASS v.surf.rst (its defaults, and tension and
smoothing tuned on the truth itself), v.surf.bspline (bicubic, one-net-cell steps); relief's
net.gridding = "fit" with its defaults (depth 0: the net itself).
Needs Debian's python3-numpy, python3-gdal, gdal-bin and grass-core.
Usage: /usr/bin/python3 bench/holdout_rasters.py build/relief [shared/data/rasters] [methods...]
(methods: words of their labels, e.g. `relief` for relief's fit alone: the others' figures do not
change with relief, and GRASS's tuned v.surf.rst takes most of the half hour the whole table takes)."""
import json, math, os, sys, tempfile
import numpy as np
from osgeo import gdal, osr

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from holdout import Box, gdal_grid, grass, inside_hull, relief_fit  # noqa: E402

gdal.UseExceptions()
relief = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else 'build/relief')
rasters = os.path.abspath(sys.argv[2] if len(sys.argv) > 2 else os.path.join(os.path.dirname(__file__), '../../shared/data/rasters'))
only = set(sys.argv[3:])
TERRAINS = {'Maungawhau (2 m)': 'volcano2hires.tif', "Holyrood Park (2.5 m)": 'holyroodpark.tif',
            'cyl_elev (0.025 deg)': 'cyl_elev.tif'}
TRUTH = 20000


def read_terrain(path):
    """The raster's nodes: lon/lat, UTM x/y (the zone of its centre), heights; NaN where no data."""
    ds = gdal.Open(path)
    gt = ds.GetGeoTransform()
    band = ds.GetRasterBand(1)
    a = band.ReadAsArray().astype(float)
    if band.GetNoDataValue() is not None: a[a == band.GetNoDataValue()] = np.nan
    h, w = a.shape
    rr, cc = np.mgrid[0:h, 0:w]
    native = np.c_[(gt[0] + (cc + 0.5) * gt[1]).ravel(), (gt[3] + (rr + 0.5) * gt[5]).ravel()]
    src = osr.SpatialReference(wkt=ds.GetProjection())
    ll = osr.SpatialReference(); ll.ImportFromEPSG(4326)
    for s in (src, ll): s.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    lonlat = np.array(osr.CoordinateTransformation(src, ll).TransformPoints(native.tolist()))[:, :2]
    lon0, lat0 = lonlat.mean(axis=0)
    epsg = (32600 if lat0 >= 0 else 32700) + int((lon0 + 180) // 6) + 1
    utm = osr.SpatialReference(); utm.ImportFromEPSG(epsg); utm.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    xy = np.array(osr.CoordinateTransformation(ll, utm).TransformPoints(lonlat.tolist()))[:, :2]
    return lonlat, xy, a.ravel(), (h, w), epsg


def samplings(shape, valid, seed):
    """Each kind of sampling as a boolean mask over the raster's nodes (row-major)."""
    h, w = shape
    n = h * w
    rr, cc = np.divmod(np.arange(n), w)
    rng = np.random.default_rng(seed)

    def at_random(count, allowed):
        out = np.zeros(n, bool)
        out[rng.choice(np.flatnonzero(allowed), count, replace=False)] = True
        return out

    def track(count):
        """The raster's nodes along a straight line at a random bearing through a random point."""
        r0, c0, bearing = rng.uniform(0, h), rng.uniform(0, w), rng.uniform(0, math.pi)
        reach = math.hypot(h, w)
        t = np.linspace(-reach, reach, int(8 * reach))
        r, c = np.rint(r0 + t * math.sin(bearing)).astype(int), np.rint(c0 + t * math.cos(bearing)).astype(int)
        on = (r >= 0) & (r < h) & (c >= 0) & (c < w)
        nodes = np.unique(r[on] * w + c[on])
        nodes = nodes[valid[nodes]]
        out = np.zeros(n, bool)
        out[nodes[np.linspace(0, len(nodes) - 1, min(count, len(nodes))).astype(int)]] = True
        return out

    kinds = {'random 2,000': lambda: at_random(2000, valid), 'random 8,000': lambda: at_random(8000, valid)}
    kinds['survey lines 2,000'] = lambda: np.logical_or.reduce([track(400) for _ in range(5)])

    def clusters():
        out = np.zeros(n, bool)
        for centre in rng.choice(np.flatnonzero(valid), 12, replace=False):
            near = np.flatnonzero(valid & (np.hypot(rr - centre // w, cc - centre % w) < 0.05 * max(h, w)))
            out[rng.choice(near, min(len(near), 170), replace=False)] = True
        return out
    kinds['clusters 2,000'] = clusters
    kinds['a hole 2,000'] = lambda: at_random(2000, valid & (np.hypot((rr - h / 2) / h, (cc - w / 2) / w) >= 0.25))
    return {k: make() & valid for k, make in kinds.items()}


def main():
    results = {}
    for terrain, file in TERRAINS.items():
        lonlat, xy, z, shape, epsg = read_terrain(os.path.join(rasters, file))
        valid = np.isfinite(z)
        lo, hi = xy[valid].min(axis=0), xy[valid].max(axis=0)
        lo, hi = lo + 0.03 * (hi - lo), hi - 0.03 * (hi - lo)  # inside the raster however UTM turns it
        for kind, picked in samplings(shape, valid, 20261207).items():
            nodes = 129 if '8,000' in kind else 65
            box = Box(np.array([lo, lo + min(hi - lo)]), min(hi - lo) / (nodes - 1))
            inbox = (xy[:, 0] >= box.x0) & (xy[:, 0] <= box.x1) & (xy[:, 1] >= box.y0) & (xy[:, 1] <= box.y1)
            picked = picked & inbox
            candidates = np.flatnonzero(valid & ~picked & inbox)
            candidates = candidates[np.random.default_rng(7).permutation(len(candidates))[:4 * TRUTH]]
            candidates = candidates[inside_hull(xy[picked], xy[candidates])][:TRUTH]
            q, want = xy[candidates], z[candidates]
            row = {'samples': int(picked.sum()), 'truth': len(candidates), 'range': [float(z[picked].min()), float(z[picked].max())]}
            rmse = lambda got: round(float(np.sqrt(np.mean((got - want) ** 2))), 2)
            with tempfile.TemporaryDirectory() as work:
                s_xy, s_z = xy[picked], z[picked]
                methods = {
                    'gdal_grid linear': lambda: gdal_grid(work, 'linear', s_xy, s_z, box, q),
                    'gdal_grid invdist': lambda: gdal_grid(work, 'invdist', s_xy, s_z, box, q),
                    'v.surf.rst defaults': lambda: grass(work, epsg, 'v.surf.rst input=pts elevation=surface', s_xy, s_z, box, q),
                    'v.surf.rst tuned': lambda: min((grass(work, epsg, f'v.surf.rst input=pts elevation=surface tension={t} smooth={s} dmin={box.spacing * 0.01}', s_xy, s_z, box, q)
                                                     for t in (10, 20, 40, 80, 160) for s in (0.1, 0.5)), key=rmse),
                    'v.surf.bspline bicubic': lambda: grass(work, epsg, f'v.surf.bspline input=pts raster_output=surface method=bicubic ew_step={box.spacing} ns_step={box.spacing}', s_xy, s_z, box, q),
                }
                for label, run in methods.items():
                    if only and not any(o in label for o in only): continue
                    try:
                        row[label] = rmse(run())
                    except Exception as e:  # a method that fails is reported, not fatal
                        row[label] = f'failed: {e}'[:80]
                if not only or any(o in 'relief fit' for o in only):
                    got, fit = relief_fit(work, lonlat[picked], s_z, box, epsg, q, 'depth = 0')
                    row['relief fit'] = rmse(got)
                    row['relief surface range at the truth'] = [round(float(v), 1) for v in (got.min(), got.max())]
                    row['relief chosen by'] = fit['smoothing_chosen_by']
                    row['relief unsupported share'] = round(fit.get('unsupported_share', 0), 3)  # none before 2026-12-07
            results[f'{terrain}: {kind}'] = row
            print(f'{terrain}: {kind}: {row}', flush=True)
    json.dump(results, open('holdout_rasters.json', 'w'), indent=1)


if __name__ == '__main__':
    main()
