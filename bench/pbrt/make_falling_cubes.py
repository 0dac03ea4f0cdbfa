#!/usr/bin/env python3
"""Write iris's falling-cubes (data/scenes/falling-cubes.json) in pbrt-v4's format, by hand
from iris's conventions (quad: size.x x size.z in y = 0, front +y; cube centred, edge size;
transforms applied in list order; camera fov vertical), for the comparison with pbrt-v4's own
bdpt (bench/pbrt/equal_time.sh, docs/results.md). Until iris can export its scenes, this file
must follow data/scenes/falling-cubes.json by hand. Materials as there: diffuse 0.65 and 0.5
(constant spectra), the wall's sRGB colour (pbrt upsamples it its own way), N-SF11 from the
same Sellmeier coefficients at 5 nm steps, the lamp D65 at luminance 50 (pbrt's "scale"
normalises the named illuminant: exposures differ, which relMSE does not see).

    python3 make_falling_cubes.py [--spp N] [--res W H] [--integrator bdpt|volpath] [--maxdepth D] [--filter box|gaussian] > out.pbrt
"""
import argparse
import math

def rot(axis, deg):
    x, y, z = axis
    n = math.sqrt(x * x + y * y + z * z)
    x, y, z = x / n, y / n, z / n
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    t = 1 - c
    return [[t * x * x + c, t * x * y - s * z, t * x * z + s * y],
            [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c]]

def apply(m, p):
    return [sum(m[i][j] * p[j] for j in range(3)) for i in range(3)]

def transform(points, normals, ops):
    for op in ops:
        if op[0] == "rotate":
            m = rot(op[1], op[2])
            points = [apply(m, p) for p in points]
            normals = [apply(m, n) for n in normals]
        else:
            points = [[p[i] + op[1][i] for i in range(3)] for p in points]
    return points, normals

def quad(sx, sz):
    x, z = sx / 2, sz / 2
    return [[-x, 0, -z], [-x, 0, z], [x, 0, z], [x, 0, -z]], [[0, 1, 0]] * 4, [[0, 1, 2], [0, 2, 3]]

def cube(size):
    h = size / 2
    pts, nrm, tri = [], [], []
    for axis in range(3):
        for sign in (-1, 1):
            n = [0, 0, 0]
            n[axis] = sign
            u = [0, 0, 0]
            v = [0, 0, 0]
            u[(axis + 1) % 3] = 1
            v[(axis + 2) % 3] = 1
            base = len(pts)
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                pts.append([n[i] * h + u[i] * a * h + v[i] * b * h for i in range(3)])
                nrm.append(n)
            # counter-clockwise seen from outside: (u x v) = n for sign +1
            if sign > 0:
                tri += [[base, base + 1, base + 2], [base, base + 2, base + 3]]
            else:
                tri += [[base, base + 2, base + 1], [base, base + 3, base + 2]]
    return pts, nrm, tri

def mesh(pts, nrm, tri):
    f = lambda v: " ".join(f"{c:.7g}" for c in v)
    return ('Shape "trianglemesh" "point3 P" [ ' + " ".join(f(p) for p in pts) + ' ]\n'
            '    "normal N" [ ' + " ".join(f(n) for n in nrm) + ' ]\n'
            '    "integer indices" [ ' + " ".join(" ".join(str(i) for i in t) for t in tri) + ' ]\n')

def sellmeier(l_nm, b, c):
    l2 = (l_nm / 1000.0) ** 2
    return math.sqrt(1 + sum(bi * l2 / (l2 - ci) for bi, ci in zip(b, c)))

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--res", type=int, nargs=2, default=[160, 120])
    ap.add_argument("--integrator", default="bdpt")
    ap.add_argument("--maxdepth", type=int, default=32)
    ap.add_argument("--filter", default="box", help="box (iris's pixel filter: each sample counts in its own pixel) or gaussian (pbrt's default)")
    a = ap.parse_args()
    b = (1.73759695, 0.313747346, 1.89878101)  # N-SF11 (Schott), as iris's data/glass_sellmeier.csv
    c = (0.013188707, 0.0623068142, 155.23629)
    eta = " ".join(f"{l} {sellmeier(l, b, c):.6f}" for l in range(360, 831, 5))
    out = []
    out.append('Scale -1 1 1  # pbrt\'s camera space is left-handed: mirror to match iris\n')
    out.append('LookAt 0 1.6 5.5  0 1.2 0  0 1 0\n')
    out.append('Camera "perspective" "float fov" [ 35 ]\n')
    out.append(f'Film "rgb" "integer xresolution" [ {a.res[0]} ] "integer yresolution" [ {a.res[1]} ] "string filename" "falling-cubes.exr"\n')
    out.append(f'Sampler "zsobol" "integer pixelsamples" [ {a.spp} ]\n')
    if a.filter == "box":
        out.append('PixelFilter "box" "float xradius" [ 0.5 ] "float yradius" [ 0.5 ]\n')
    out.append(f'Integrator "{a.integrator}" "integer maxdepth" [ {a.maxdepth} ]\n')
    out.append('WorldBegin\n')
    out.append('MakeNamedMaterial "floor" "string type" "diffuse" "spectrum reflectance" [ 360 0.65 830 0.65 ]\n')
    out.append('MakeNamedMaterial "wall" "string type" "diffuse" "rgb reflectance" [ 0.62 0.66 0.74 ]\n')
    out.append('MakeNamedMaterial "lamp-housing" "string type" "diffuse" "spectrum reflectance" [ 360 0.5 830 0.5 ]\n')
    out.append(f'MakeNamedMaterial "flint" "string type" "dielectric" "spectrum eta" [ {eta} ]\n')
    def shape(material, geom, ops, light=False):
        p, n = transform(geom[0], geom[1], ops)
        t = geom[2]
        s = f'AttributeBegin\n  NamedMaterial "{material}"\n'
        if light:
            s += '  AreaLightSource "diffuse" "spectrum L" "stdillum-D65" "float scale" [ 50 ]\n'
        return s + "  " + mesh(p, n, t) + "AttributeEnd\n"
    out.append(shape("floor", quad(8, 5), [("translate", [0, 0, 0.5])]))
    out.append(shape("wall", quad(8, 5), [("rotate", [1, 0, 0], 90), ("translate", [0, 2.5, -2])]))
    out.append(shape("lamp-housing", quad(0.8, 0.8), [("rotate", [1, 0, 0], 180), ("translate", [0.4, 3.6, 0.8])], light=True))
    for size, ops in [
        (0.8, [("rotate", [0, 1, 0], 25), ("translate", [-1.4, 0.4001, -0.3])]),
        (0.45, [("rotate", [1, 0.2, 0], 20), ("translate", [0.9, 0.5, 1.0])]),
        (0.6, [("rotate", [1, 1, 0], 35), ("translate", [0.1, 1.1, 0.4])]),
        (0.7, [("rotate", [1, 0, 1], 50), ("translate", [1.4, 1.7, -0.5])]),
        (0.5, [("rotate", [0.3, 1, 0.5], 70), ("translate", [-0.6, 2.3, -0.8])]),
    ]:
        out.append(shape("flint", cube(size), ops))
    print("".join(out), end="")

if __name__ == "__main__":
    main()
