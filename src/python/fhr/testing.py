"""Hypothesis strategies of random manifold meshes, for property tests of your own code.

A mesh is drawn as a recipe of `fhr generate` (genus, face count, seed, noise, and on request
holes and components) and built by the C++ generator, so a failing example is reproducible from its
recipe on any machine. Hypothesis shrinks the recipe: lower genus, fewer holes and components, fewer
faces, seed 0, no noise -- the same notion of "smaller" as the C++ RapidCheck generator
(<fhr/testing/rapidcheck.hpp>). By default the meshes are closed and connected, the paper's input
class; `holes=(1, 5), components=(1, 3)` gives surfaces with boundary loops
and several components (genus and holes are totals over the components).

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
# The embedded families of the generator (spec/generator.md); "immersed" is drawn only when asked for.
EMBEDDED_FAMILIES = ("block", "smooth", "quality", "valence", "density", "degenerate")


@dataclass(frozen=True)
class Recipe:
    """The options of `fhr generate` that make one mesh."""

    genus: int
    faces: int
    seed: int
    noise: float
    holes: int = 0
    components: int = 1
    family: str = "block"

    def command(self, out="mesh.off"):
        """The command line that writes this mesh to a file."""
        family = " --family %s" % self.family if self.family != "block" else ""
        holes = " --holes %d" % self.holes if self.holes else ""
        components = " --components %d" % self.components if self.components != 1 else ""
        noise = " --noise %r" % self.noise if self.noise else ""
        return "fhr generate%s --genus %d%s%s --faces %d --seed %d%s --out %s" % (
            family, self.genus, holes, components, self.faces, self.seed, noise, out)


@dataclass(frozen=True)
class Mesh:
    """A generated mesh: its recipe, V ((n, 3) float64) and F ((m, 3) int64)."""

    recipe: Recipe
    V: np.ndarray = field(repr=False, compare=False)
    F: np.ndarray = field(repr=False, compare=False)

    def __repr__(self):
        return "<%s: %d vertices, %d faces>" % (self.recipe.command(), len(self.V), len(self.F))


@st.composite
def recipes(draw, genus=(0, 4), faces=(12, 2000), holes=(0, 0), components=(1, 1), families=("block",)):
    """Recipes with genus, holes and components in the closed ranges given (holes and components are
    drawn only when their range has more than one value, so the defaults spend no draw on
    these two knobs), a family among `families` (drawn only when there is more than one; its
    knobs at their defaults) and a face count in `faces`, raised to the generator's minimum for what
    was drawn, even when there are no holes. Shrinks toward the first family, the lowest genus, the
    fewest holes and components, the fewest faces, seed 0 and no noise (noise only for block)."""
    def draw_if_varies(bounds):
        return bounds[0] if bounds[0] == bounds[1] else draw(st.integers(bounds[0], bounds[1]))
    family = families[0] if len(families) == 1 else families[draw(st.integers(0, len(families) - 1))]
    g = draw(st.integers(genus[0], genus[1]))
    b = draw_if_varies(holes)
    c = draw_if_varies(components)
    step = 2 if b == 0 else 1  # without holes the face count is even
    fewest = _fhr.min_faces(g, b, c, family)
    least = max(fewest, faces[0] + (faces[0] % 2 if step == 2 else 0))
    if least > faces[1]:
        raise ValueError("no %s mesh of genus %d with %d holes in %d components has at most %d faces (the fewest are %d)"
                         % (family, g, b, c, faces[1], fewest))
    n = least + step * draw(st.integers(0, (faces[1] - least) // step))
    seed = draw(st.integers(0, 2**63 - 1))
    noise = NOISES[draw(st.integers(0, len(NOISES) - 1))] if family == "block" else 0.0
    return Recipe(g, n, seed, noise, b, c, family)


def meshes(genus=(0, 4), faces=(12, 2000), holes=(0, 0), components=(1, 1), families=("block",)):
    """Random orientable manifold meshes (see recipes), as Mesh values: closed and connected unless
    `holes` or `components` ask for more, block meshes unless `families` asks for others."""
    def build(r):
        V, F = _fhr.generate(r.genus, r.faces, r.seed, r.noise, r.holes, r.components, r.family)
        return Mesh(r, V, F)
    return recipes(genus, faces, holes, components, families).map(build)
