"""Hypothesis strategies of random closed manifold meshes, for property tests of your own code.

A mesh is drawn as a recipe of `fhr generate` (genus, face count, seed, noise) and built by the C++
generator, so a failing example is reproducible from its recipe on any machine. Hypothesis shrinks
the recipe: lower genus, fewer faces, seed 0, no noise -- the same notion of "smaller" as the C++
RapidCheck generator (<fhr/testing/rapidcheck.hpp>).

    from hypothesis import given
    import fhr.testing

    @given(fhr.testing.meshes(genus=(0, 2), faces=(100, 2000)))
    def test_my_code(mesh):
        V, F = mesh.V, mesh.F
        ...
"""

from dataclasses import dataclass, field

import numpy as np
from hypothesis import strategies as st

from . import _fhr

NOISES = (0.0, 0.05, 0.1, 0.25)  # exact in decimal: the shown command reproduces the mesh


@dataclass(frozen=True)
class Recipe:
    """The options of `fhr generate` that make one mesh."""

    genus: int
    faces: int
    seed: int
    noise: float

    def command(self, out="mesh.off"):
        """The command line that writes this mesh to a file."""
        noise = " --noise %r" % self.noise if self.noise else ""
        return "fhr generate --genus %d --faces %d --seed %d%s --out %s" % (self.genus, self.faces, self.seed, noise, out)


@dataclass(frozen=True)
class Mesh:
    """A generated mesh: its recipe, V ((n, 3) float64) and F ((m, 3) int64)."""

    recipe: Recipe
    V: np.ndarray = field(repr=False, compare=False)
    F: np.ndarray = field(repr=False, compare=False)

    def __repr__(self):
        return "<%s: %d vertices, %d faces>" % (self.recipe.command(), len(self.V), len(self.F))


@st.composite
def recipes(draw, genus=(0, 4), faces=(12, 2000)):
    """Recipes with genus in the closed range `genus` and an even face count in `faces` (raised to the
    generator's minimum for the genus drawn). Shrinks toward the lowest genus, the fewest faces, seed
    0 and no noise."""
    lo_genus, hi_genus = genus
    g = draw(st.integers(lo_genus, hi_genus))
    least = max(_fhr.min_faces(g), faces[0] + faces[0] % 2)
    if least > faces[1]:
        raise ValueError("no mesh of genus %d has at most %d faces (the fewest are %d)" % (g, faces[1], _fhr.min_faces(g)))
    n = least + 2 * draw(st.integers(0, (faces[1] - least) // 2))
    seed = draw(st.integers(0, 2**63 - 1))
    noise = NOISES[draw(st.integers(0, len(NOISES) - 1))]
    return Recipe(g, n, seed, noise)


def meshes(genus=(0, 4), faces=(12, 2000)):
    """Random closed orientable manifold meshes (see recipes), as Mesh values."""
    def build(r):
        V, F = _fhr.generate(r.genus, r.faces, r.seed, r.noise)
        return Mesh(r, V, F)
    return recipes(genus, faces).map(build)
