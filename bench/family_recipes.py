"""The recipes of the generator's family campaigns (`./run families`, bench/generator_stats.py):
mesh i of family f drawn from (seed, f, i) alone — Python's random.Random seeded with the string
"S f i" (SHA-512 of the string: the same on every platform and Python >= 3.2) — so a recipe does
not depend on the campaign's other meshes, on which families are asked for, or on the shard:
genus in [0, --genus-max] (default 3), boundary loops in [0, --holes-max] (default 5), components
in [1, --components-max] (default 3), genus and loops being totals over the components as in `fhr
generate`; faces uniform in [max(--faces-min, min_faces), --faces-max] (default 1,000–20,000; the
even ones without holes), min_faces being the family's least for that topology (`fhr generate
--min-faces`); a seed below 2^63; the family's knobs at their defaults."""
import functools
import random
import subprocess

import campaign
import certify

EMBEDDED = ("block", "smooth", "quality", "valence", "density", "degenerate")


def add_options(parser, families=EMBEDDED):
    parser.add_argument("--families", default=",".join(families), help="comma-separated (default: %s)" % ",".join(families))
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--genus-max", type=int, default=3)
    parser.add_argument("--holes-max", type=int, default=5)
    parser.add_argument("--components-max", type=int, default=3)
    parser.add_argument("--faces-min", type=int, default=1000)
    parser.add_argument("--faces-max", type=int, default=20000)


@functools.lru_cache(maxsize=None)
def min_faces(fhr, family, genus, holes, components):
    proc = subprocess.run([fhr, "generate", "--family", family, "--genus", str(genus), "--holes", str(holes),
                           "--components", str(components), "--min-faces"], capture_output=True, text=True)
    if proc.returncode != 0:
        raise campaign.CampaignError("fhr generate --family %s --min-faces: %s" % (family, certify.error_line(proc.stderr)))
    return int(proc.stdout)


def recipe(fhr, options, family, i):
    """Mesh i of the family: its `fhr generate` arguments (without --out) and sizes."""
    rng = random.Random("%d %s %d" % (options.seed, family, i))
    genus = rng.randint(0, options.genus_max)
    holes = rng.randint(0, options.holes_max)
    components = rng.randint(1, options.components_max)
    least = max(options.faces_min, min_faces(fhr, family, genus, holes, components))
    if least > options.faces_max:
        raise campaign.CampaignError("%s meshes of genus %d with %d holes in %d components need %d faces, more than --faces-max"
                                     % (family, genus, holes, components, least))
    faces = rng.randint(least, options.faces_max) if holes else 2 * rng.randint((least + 1) // 2, options.faces_max // 2)
    args = ([] if family == "block" else ["--family", family]) + ["--genus", str(genus)]
    args += (["--holes", str(holes)] if holes else []) + (["--components", str(components)] if components > 1 else [])
    args += ["--faces", str(faces), "--seed", str(rng.getrandbits(63))]
    return args, faces, genus, holes, components
