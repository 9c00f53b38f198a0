"""Stand-in for robodk.robomath: the Mat class as far as roprec's RoboDK app uses it.

Mat(rows) takes a list of rows (a list of lists) or a flat list (a column, as RoboDK returns joints);
Rows() returns the rows; list() the first column as a list (RoboDK's Mat.list()).
"""


class Mat(object):
    """A matrix (RoboDK robomath.Mat): a 4x4 pose in mm, or a column of joints."""

    def __init__(self, rows=None, ncols=None):
        if ncols is not None:
            self.rows = [[0.0] * ncols for _ in range(max(rows, 1))]
        elif rows is None:
            self.rows = [[0.0] * 4 for _ in range(4)]
        elif isinstance(rows, Mat):
            self.rows = [list(r) for r in rows.rows]
        elif len(rows) > 0 and not isinstance(rows[0], (list, tuple)):
            self.rows = [[float(x)] for x in rows]  # a flat list is a column
        else:
            self.rows = [[float(x) for x in r] for r in rows]

    def Rows(self):
        """The matrix as a list of rows."""
        return self.rows

    def list(self):
        """The first column as a list."""
        return [r[0] for r in self.rows]

    def size(self, dim=None):
        """(rows, columns), or one of them."""
        s = (len(self.rows), len(self.rows[0]) if self.rows else 0)
        return s if dim is None else s[dim]

    def __repr__(self):
        return "Mat(%r)" % (self.rows,)
