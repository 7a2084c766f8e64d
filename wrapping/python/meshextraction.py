"""NumPy for the meshes of itk-meshextraction: points and triangles as arrays, and
meshes made from arrays, for itk.Mesh[itk.D, 3] and itk.QuadEdgeMesh[itk.D, 3].

    import itk
    from itk import meshextraction
    points, triangles = meshextraction.arrays_from_mesh(mesh)       # (n, 3) float, (m, 3) int
    mesh = meshextraction.mesh_from_arrays(points, triangles)        # itk.Mesh[itk.D, 3]
    qe = meshextraction.mesh_from_arrays(points, triangles, itk.QuadEdgeMesh[itk.D, 3])

Points are physical coordinates (mm); each triangle lists three point indices,
counter-clockwise seen from outside. ITK's meshes hold coordinates as 32-bit floats.
A QuadEdgeMesh is made through itk.SurfaceMeshConvertFilter, which refuses triangles
that are not manifold or not consistently oriented."""
import numpy as np

__all__ = ["arrays_from_mesh", "mesh_from_arrays"]

# ITK's CommonEnums::CellGeometry values in itk::Mesh's cell arrays.
_VERTEX_CELL, _LINE_CELL, _TRIANGLE_CELL = 0, 1, 2


def _mesh_types():
    import itk

    return itk.Mesh[itk.D, 3], itk.QuadEdgeMesh[itk.D, 3]


def arrays_from_mesh(mesh):
    """The points, an (n, 3) float64 array, and the triangles, an (m, 3) int64 array of
    point indices, of an itk.Mesh[itk.D, 3] or itk.QuadEdgeMesh[itk.D, 3]. Vertex and
    line cells (a QuadEdgeMesh's edges) are left out; a face of more than three corners
    is a ValueError (triangulate it first, e.g. through a QuadEdgeMesh)."""
    import itk

    mesh_type, qe_type = _mesh_types()
    if isinstance(mesh, qe_type):
        mesh = itk.surface_mesh_convert_filter(mesh, ttype=(qe_type, mesh_type))
    elif not isinstance(mesh, mesh_type):
        raise TypeError("arrays_from_mesh takes an itk.Mesh[itk.D, 3] or itk.QuadEdgeMesh[itk.D, 3], not %s"
                        % type(mesh).__name__)
    if mesh.GetNumberOfPoints() == 0:
        points = np.zeros((0, 3))
    else:
        points = np.asarray(itk.array_from_vector_container(mesh.GetPoints()), dtype=np.float64).reshape(-1, 3)
    if mesh.GetNumberOfCells() == 0:
        return points, np.zeros((0, 3), dtype=np.int64)
    # The cells array: for each cell its type, its number of points, then the points.
    cells = np.asarray(itk.array_from_vector_container(mesh.GetCellsArray()), dtype=np.int64)
    if cells.size % 5 == 0:
        rows = cells.reshape(-1, 5)
        if (rows[:, 0] == _TRIANGLE_CELL).all() and (rows[:, 1] == 3).all():
            return points, rows[:, 2:].copy()
    triangles = []
    i = cell = 0
    while i < cells.size:
        kind, count = cells[i], cells[i + 1]
        corners = cells[i + 2:i + 2 + count]
        if kind not in (_VERTEX_CELL, _LINE_CELL):
            if count != 3:
                raise ValueError("arrays_from_mesh: cell %d has %d corners; only triangles are taken" % (cell, count))
            triangles.append(corners)
        i += 2 + count
        cell += 1
    return points, np.array(triangles, dtype=np.int64).reshape(-1, 3)


def mesh_from_arrays(points, triangles, mesh_type=None):
    """A mesh (itk.Mesh[itk.D, 3] unless mesh_type is itk.QuadEdgeMesh[itk.D, 3]) of
    points, an (n, 3) array of finite coordinates, and triangles, an (m, 3) array of
    indices below n. Bad arrays are a ValueError naming the problem; for a QuadEdgeMesh,
    triangles that are not manifold or not consistently oriented are a RuntimeError."""
    import itk

    plain_type, qe_type = _mesh_types()
    mesh_type = plain_type if mesh_type is None else mesh_type
    if mesh_type not in (plain_type, qe_type):
        raise ValueError("mesh_from_arrays makes an itk.Mesh[itk.D, 3] or itk.QuadEdgeMesh[itk.D, 3], not %s"
                         % getattr(mesh_type, "__name__", mesh_type))
    points = np.asarray(points, dtype=np.float64)
    triangles = np.asarray(triangles)
    if points.ndim != 2 or points.shape[1] != 3:
        raise ValueError("points must be an (n, 3) array, got shape %s" % (points.shape,))
    if not np.isfinite(points).all():
        bad = np.argwhere(~np.isfinite(points))[0]
        raise ValueError("point %d has a coordinate that is not finite: %r" % (bad[0], points[bad[0]].tolist()))
    if triangles.size == 0:
        triangles = triangles.reshape(0, 3).astype(np.int64)
    if triangles.ndim != 2 or triangles.shape[1] != 3:
        raise ValueError("triangles must be an (m, 3) array of point indices, got shape %s" % (triangles.shape,))
    if not np.issubdtype(triangles.dtype, np.integer):
        raise ValueError("triangles must hold integer point indices, got %s" % triangles.dtype)
    if triangles.size and (triangles.min() < 0 or triangles.max() >= len(points)):
        t = int(np.argwhere((triangles < 0) | (triangles >= len(points)))[0][0])
        raise ValueError("triangle %d names point %s, but there are %d points"
                         % (t, triangles[t].tolist(), len(points)))
    mesh = plain_type.New()
    if len(points):
        mesh.SetPoints(itk.vector_container_from_array(points.astype(np.float32).ravel()))
    if len(triangles):
        cells = np.column_stack([np.full(len(triangles), _TRIANGLE_CELL), np.full(len(triangles), 3), triangles])
        mesh.SetCellsArray(itk.vector_container_from_array(cells.astype(np.uint64).ravel()))
    if mesh_type is qe_type:
        return itk.surface_mesh_convert_filter(mesh, ttype=(plain_type, qe_type))
    return mesh
