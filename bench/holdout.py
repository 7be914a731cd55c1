#!/usr/bin/python3
"""Hold-out accuracy of gridding methods on the shared lattices (bench/RESULTS.md).

For each lattice (shared/data/volcano_full.csv, topobathy_full.csv) and each kind of sampling
(the shared random set; 40 % at random; survey lines; clusters; a hole), the samples go in and the
rest of the lattice is the truth. Every method makes its surface over the same box, in the same UTM
frame, and is read at the truth's nodes that lie inside the samples' convex hull (bilinear from a
grid a quarter of the lattice's spacing, or finer): RMSE in metres.

Methods: gdal_grid -a linear and -a invdist; GRASS v.surf.rst (its defaults, and tension and
smoothing tuned on the truth, every point kept), v.surf.bspline (bicubic, one-lattice-cell steps);
relief's net.gridding = "fit" (GCV) with three schemes, its net at the lattice's spacing; kriging
with an exponential covariance and a nugget fitted by maximum likelihood (up to 2,500 samples: its
cost grows as N^3, some minutes at 2,000).
Needs Debian's python3-numpy, python3-gdal, gdal-bin, grass-core and python3-sklearn.
Usage: /usr/bin/python3 bench/holdout.py build/relief [shared/data] [methods...]"""
import json, math, os, shutil, subprocess, sys, tempfile
import numpy as np
from osgeo import gdal, ogr, osr

gdal.UseExceptions()
relief = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else 'build/relief')
data = os.path.abspath(sys.argv[2] if len(sys.argv) > 2 else os.path.join(os.path.dirname(__file__), '../../shared/data'))
only = set(sys.argv[3:])
LATTICES = {'volcano': ('volcano_full.csv', 'volcano_samples_1000_seed20251124.csv', 32760),
            'topobathy': ('topobathy_full.csv', 'topobathy_samples_2000_seed20251123.csv', 32610)}
SCHEMES = {'relief fit, gentle (paper 001)': ('preset', 'gentle-mountains'),
           'relief fit, cubic B-spline (paper 004)': ('scheme', 'ternary-bspline'),
           'relief fit, dlg4': ('scheme', 'dlg4')}


def read_lattice(name):
    full, samples, epsg = LATTICES[name]
    rows = [l.strip() for l in open(os.path.join(data, full)).read().splitlines()[1:]]
    picked = set(l.strip() for l in open(os.path.join(data, samples)).read().splitlines()[1:])
    lonlat = np.array([[float(v) for v in r.split(',')[:2]] for r in rows])
    z = np.array([float(r.split(',')[2]) for r in rows])
    src, dst = osr.SpatialReference(), osr.SpatialReference()
    src.ImportFromEPSG(4326), dst.ImportFromEPSG(epsg)
    for s in (src, dst): s.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    xy = np.array(osr.CoordinateTransformation(src, dst).TransformPoints(lonlat.tolist()))[:, :2]
    shared = np.array([r in picked for r in rows])
    meta = json.load(open(os.path.join(data, 'metadata.json')))[name]
    return lonlat, xy, z, shared, (meta['nrows'], meta['ncols']), epsg


def samplings(xy, shape, shared):
    """Each kind of sampling as a boolean mask over the lattice's nodes (row-major, north first)."""
    n = len(xy)
    rows, cols = shape
    r, c = np.divmod(np.arange(n), cols)
    rng = np.random.default_rng(20261205)
    centre = xy.mean(axis=0)
    span = xy.max(axis=0) - xy.min(axis=0)
    kinds = {'random (the shared set)': shared}
    kinds['random, 40 %'] = rng.random(n) < 0.4
    kinds['survey lines'] = (r % 8 == 0) | (c % 12 == 0)
    clusters = np.zeros(n, bool)
    for centre_index in rng.choice(n, 25, replace=False):
        clusters |= np.hypot(*(xy - xy[centre_index]).T) < 0.06 * span.max()
    kinds['clusters'] = clusters
    hole = np.hypot(*((xy - centre) / span).T) < 0.2
    kinds['a hole'] = (rng.random(n) < 0.3) & ~hole
    return kinds


def inside_hull(points, queries):
    hull = ogr.Geometry(ogr.wkbMultiPoint)
    for x, y in points:
        p = ogr.Geometry(ogr.wkbPoint); p.AddPoint_2D(float(x), float(y)); hull.AddGeometry(p)
    hull = hull.ConvexHull()
    out = np.zeros(len(queries), bool)
    for i, (x, y) in enumerate(queries):
        p = ogr.Geometry(ogr.wkbPoint); p.AddPoint_2D(float(x), float(y))
        out[i] = hull.Contains(p)
    return out


def bilinear(grid, x0, y0, dx, dy, q):
    """grid[row, col], row 0 at y0 (south), col 0 at x0."""
    u, v = (q[:, 0] - x0) / dx, (q[:, 1] - y0) / dy
    c0 = np.clip(np.floor(u).astype(int), 0, grid.shape[1] - 2)
    r0 = np.clip(np.floor(v).astype(int), 0, grid.shape[0] - 2)
    fu, fv = u - c0, v - r0
    return ((1 - fv) * ((1 - fu) * grid[r0, c0] + fu * grid[r0, c0 + 1]) +
            fv * ((1 - fu) * grid[r0 + 1, c0] + fu * grid[r0 + 1, c0 + 1]))


def read_tif(path):
    ds = gdal.Open(path)
    gt = ds.GetGeoTransform()
    a = ds.GetRasterBand(1).ReadAsArray().astype(float)[::-1]  # south row first
    x0 = gt[0] + 0.5 * gt[1]
    y0 = gt[3] + (ds.RasterYSize - 0.5) * gt[5]
    return a, x0, y0, gt[1], -gt[5]


def write_points(path, xy, z):
    with open(path, 'w') as f:
        f.write('x,y,z\n')
        for (x, y), v in zip(xy, z): f.write(f'{x:.3f},{y:.3f},{v}\n')


class Box:
    def __init__(self, xy, spacing):
        lo, hi = xy.min(axis=0), xy.max(axis=0)
        self.spacing = spacing
        self.cols = int(math.floor((hi[0] - lo[0]) / spacing)) + 1
        self.rows = int(math.floor((hi[1] - lo[1]) / spacing)) + 1
        self.x0, self.y0 = lo[0], lo[1]
        self.x1, self.y1 = lo[0] + (self.cols - 1) * spacing, lo[1] + (self.rows - 1) * spacing


def gdal_grid(work, algorithm, xy, z, box, q):
    csv = os.path.join(work, 'pts.csv'); write_points(csv, xy, z)
    vrt = os.path.join(work, 'pts.vrt')
    open(vrt, 'w').write(f'<OGRVRTDataSource><OGRVRTLayer name="pts"><SrcDataSource>{csv}</SrcDataSource>'
                         '<GeometryType>wkbPoint</GeometryType><GeometryField encoding="PointFromColumns" x="x" y="y" z="z"/>'
                         '</OGRVRTLayer></OGRVRTDataSource>')
    fine = box.spacing / 4
    w, h = int(round((box.x1 - box.x0) / fine)) + 1, int(round((box.y1 - box.y0) / fine)) + 1
    out = os.path.join(work, 'g.tif')
    subprocess.run(['gdal_grid', '-q', '-a', algorithm, '-txe', str(box.x0 - fine / 2), str(box.x1 + fine / 2),
                    '-tye', str(box.y1 + fine / 2), str(box.y0 - fine / 2), '-outsize', str(w), str(h),
                    '-ot', 'Float64', '-l', 'pts', vrt, out], check=True)
    return bilinear(*read_tif(out), q)


def grass(work, epsg, module_args, xy, z, box, q):
    csv = os.path.join(work, 'pts.txt')
    with open(csv, 'w') as f:
        for (x, y), v in zip(xy, z): f.write(f'{x:.3f}|{y:.3f}|{v}\n')
    fine = box.spacing / 4
    out = os.path.join(work, 'grass.tif')
    script = os.path.join(work, 'g.sh')
    open(script, 'w').write(f'''set -e
g.region n={box.y1 + fine / 2} s={box.y0 - fine / 2} e={box.x1 + fine / 2} w={box.x0 - fine / 2} res={fine} -a --quiet
v.in.ascii input={csv} output=pts separator=pipe z=3 -z --quiet --overwrite
{module_args} --quiet --overwrite
r.out.gdal input=surface output={out} type=Float64 --quiet --overwrite
''')
    loc = os.path.join(work, 'loc')
    shutil.rmtree(loc, ignore_errors=True)
    subprocess.run(['grass', '-c', f'EPSG:{epsg}', loc, '--exec', 'bash', script], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return bilinear(*read_tif(out), q)


def kriging(xy, z, spacing, q, nu):
    """Kriging as a Gaussian process: a Matern covariance of smoothness nu (1/2: the exponential) and
    a nugget, their parameters by maximum likelihood (scikit-learn). O(N^3): at most 2,500 samples."""
    if len(z) > 2500: raise RuntimeError(f'skipped: {len(z)} samples (at most 2,500)')
    from sklearn.gaussian_process import GaussianProcessRegressor
    from sklearn.gaussian_process.kernels import ConstantKernel, Matern, WhiteKernel
    kernel = ConstantKernel() * Matern(length_scale=5.0, nu=nu) + WhiteKernel(0.01)
    gp = GaussianProcessRegressor(kernel, normalize_y=True, random_state=0).fit(xy / spacing, z)
    return gp.predict(q / spacing)


def relief_fit(work, lonlat, z, box, epsg, q, subdivision='depth = 2'):
    """relief's net.gridding = "fit" over `box` (its [subdivision] keys as given), read at q; and the
    sidecar's net.fit."""
    csv = os.path.join(work, 's.csv')
    with open(csv, 'w') as f:
        f.write('lon,lat,elev\n')
        for (lon, lat), v in zip(lonlat, z): f.write(f'{lon:.8f},{lat:.8f},{v}\n')
    open(os.path.join(work, 's.toml'), 'w').write(f'''[samples]
path = "s.csv"
[frame]
kind = "utm"
zone = "{epsg % 100}{'N' if epsg < 32700 else 'S'}"
[net]
extent_m = [{box.x0}, {box.y0}, {box.x1}, {box.y1}]
spacing_m = {box.spacing}
gridding = "fit"
[subdivision]
{subdivision}
''')
    surface = os.path.join(work, 'surface.csv')
    subprocess.run([relief, 'compile', '-q', os.path.join(work, 's.toml'), '-o', os.path.join(work, 's.pov'),
                    '--dump-surface', surface], check=True)
    pts = np.loadtxt(surface, delimiter=',', skiprows=1)
    xs, ys = np.unique(pts[:, 0]), np.unique(pts[:, 1])
    grid = pts[:, 2].reshape(len(ys), len(xs))
    fit = json.load(open(os.path.join(work, 's.json')))['net']['fit']
    return bilinear(grid, xs[0], ys[0], xs[1] - xs[0], ys[1] - ys[0], q), fit


def main():
    results = {}
    for name in LATTICES:
        lonlat, xy, z, shared, shape, epsg = read_lattice(name)
        spacing = float(np.median(np.hypot(*np.diff(xy[:2], axis=0).T)))
        spacing = float(np.hypot(*(xy[1] - xy[0])))
        box = Box(xy, spacing)
        for kind, picked in samplings(xy, shape, shared).items():
            truth = ~picked & inside_hull(xy[picked], xy)
            q, want = xy[truth], z[truth]
            row = {'samples': int(picked.sum()), 'truth': int(truth.sum())}
            with tempfile.TemporaryDirectory() as work:
                methods = {
                    'gdal_grid linear': lambda: gdal_grid(work, 'linear', xy[picked], z[picked], box, q),
                    'gdal_grid invdist': lambda: gdal_grid(work, 'invdist', xy[picked], z[picked], box, q),
                    'v.surf.rst defaults': lambda: grass(work, epsg, 'v.surf.rst input=pts elevation=surface', xy[picked], z[picked], box, q),
                    'v.surf.rst tuned': lambda: min((grass(work, epsg, f'v.surf.rst input=pts elevation=surface tension={t} smooth={s} dmin={spacing * 0.01}', xy[picked], z[picked], box, q)
                                                     for t in (10, 20, 40, 80, 160) for s in (0.1, 0.5)), key=lambda v: float(np.sqrt(np.mean((v - want) ** 2)))),
                    'v.surf.bspline bicubic': lambda: grass(work, epsg, f'v.surf.bspline input=pts raster_output=surface method=bicubic ew_step={spacing} ns_step={spacing}', xy[picked], z[picked], box, q),
                    'kriging, exponential (ML)': lambda: kriging(xy[picked], z[picked], spacing, q, 0.5),
                }
                for label, (k, scheme) in SCHEMES.items():
                    methods[label] = (lambda k=k, scheme=scheme: relief_fit(work, lonlat[picked], z[picked], box, epsg, q,
                                                                            f'{k} = "{scheme}"\ndepth = 2')[0])
                for label, run in methods.items():
                    if only and not any(o in label for o in only): continue
                    try:
                        got = run()
                        row[label] = round(float(np.sqrt(np.mean((got - want) ** 2))), 2)
                    except Exception as e:  # a method that fails is reported, not fatal
                        row[label] = f'failed: {e}'[:80]
            results[f'{name}: {kind}'] = row
            print(f'{name}: {kind}: {row}', flush=True)
    json.dump(results, open('holdout.json', 'w'), indent=1)


if __name__ == '__main__':
    main()
