"""The exceptions of minksum (raised by the extension module)."""


class InputError(Exception):
    """The data is bad: a malformed file, an open or non-convex mesh, a degenerate point set.

    ``file`` names the input (a path, a catalog name, or ``""`` for data given
    in memory), ``place`` where in it ("line 12", "face 3"; may be empty) and
    ``problem`` what is wrong.  ``str(e)`` is "FILE: PLACE: PROBLEM", the line
    the command ``minksum`` prints.
    """

    def __init__(self, file: str, place: str, problem: str) -> None:
        super().__init__(file, place, problem)
        self.file = file
        self.place = place
        self.problem = problem

    def __str__(self) -> str:
        text = self.file or "<input>"
        if self.place:
            text += ": " + self.place
        return text + ": " + self.problem


class NotConvexError(InputError):
    """A closed surface that is not exactly convex (what a mesh rounded by another tool gives).

    ``minksum.load(path, hull=True)`` and ``Polytope.hull`` accept such data by
    taking the convex hull of the points.
    """
