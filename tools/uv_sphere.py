"""A UV sphere for the scene scripts (make_textured_scene.py, make_material_grid.py)."""
import math


def sphere(radius, stacks, slices):
    """Positions, unit normals, texture coordinates (s along the equator, t from the north pole) and
    counter-clockwise triangles of a sphere of `radius` about the origin."""
    positions, normals, texcoords, triangles = [], [], [], []
    for i in range(stacks + 1):
        theta = math.pi * i / stacks
        for j in range(slices + 1):
            phi = 2 * math.pi * j / slices
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            positions.append(tuple(radius * c for c in n))
            normals.append(n)
            texcoords.append((j / slices, i / stacks))
    for i in range(stacks):
        for j in range(slices):
            a = i * (slices + 1) + j
            b = a + slices + 1
            if i > 0:
                triangles.append((a, b, a + 1))
            if i < stacks - 1:
                triangles.append((a + 1, b, b + 1))
    return positions, normals, texcoords, triangles
