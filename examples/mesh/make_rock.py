#!/usr/bin/env python3
"""Writes balanced_rock.obj: a rock-like closed mesh (x east, y north, z up, metres) for `topple body`.

A star-shaped lumpy ellipsoid (semi-axes 0.9 x 0.6 x 0.7 m, radius modulated by a few low-order harmonics, no
randomness) whose lowest part is flattened onto the plane z = 0, giving a small base about 0.4 m across under a
body 1.8 m long: a precariously balanced rock (alpha about 9 deg toward the west). The harmonics put the centre of
mass off the base's centre, so b1 != b2 in most planes. Run: python3 examples/mesh/make_rock.py > examples/mesh/balanced_rock.obj
"""
import math

N_LON, N_LAT = 32, 16
A, B, C = 0.9, 0.6, 0.7
CUT = -0.68  # the plane (before lifting) onto which the lowest points are flattened


def radius(theta, phi):
    return 1.0 + 0.08 * math.sin(3 * phi) * math.sin(theta) ** 2 + 0.05 * math.cos(2 * theta + phi) \
        + 0.04 * math.cos(5 * phi + 1.0) * math.sin(theta)


def point(theta, phi):
    r = radius(theta, phi)
    x = A * r * math.sin(theta) * math.cos(phi)
    y = B * r * math.sin(theta) * math.sin(phi)
    z = C * r * math.cos(theta)
    x += 0.12 * max(z, 0.0)  # lean the top toward the east
    return [x, y, max(z, CUT)]


verts = [[0.0, 0.0, C * radius(0.0, 0.0)]]  # north pole
for i in range(1, N_LAT):
    theta = math.pi * i / N_LAT
    for j in range(N_LON):
        verts.append(point(theta, 2 * math.pi * j / N_LON))
south = [0.0, 0.0, CUT]
verts.append(south)
faces = []
ring = lambda i, j: 1 + (i - 1) * N_LON + j % N_LON
for j in range(N_LON):
    faces.append((0, ring(1, j), ring(1, j + 1)))
for i in range(1, N_LAT - 1):
    for j in range(N_LON):
        a, b, c, d = ring(i, j), ring(i, j + 1), ring(i + 1, j), ring(i + 1, j + 1)
        faces.append((a, c, d))
        faces.append((a, d, b))
last = len(verts) - 1
for j in range(N_LON):
    faces.append((ring(N_LAT - 1, j + 1), ring(N_LAT - 1, j), last))

print("# balanced_rock.obj: written by examples/mesh/make_rock.py for `topple body` (x east, y north, z up, metres)")
for x, y, z in verts:
    print(f"v {x:.6f} {y:.6f} {z - CUT:.6f}")
for a, b, c in faces:
    print(f"f {a + 1} {b + 1} {c + 1}")
