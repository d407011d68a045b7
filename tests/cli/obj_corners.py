"""The face corners of an OBJ file as (x, y, z, u, v) tuples, in face order: the CLI tests' independent reader."""


def obj_corners(path):
    positions, uvs, corners = [], [], []
    for line in open(path):
        words = line.split()
        if not words:
            continue
        if words[0] == 'v':
            positions.append(tuple(map(float, words[1:4])))
        elif words[0] == 'vt':
            uvs.append(tuple(map(float, words[1:3])))
        elif words[0] == 'f':
            for corner in words[1:]:
                index = corner.split('/')
                corners.append(positions[int(index[0]) - 1] + uvs[int(index[1]) - 1])
    return corners
