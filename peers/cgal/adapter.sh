# The body of every CGAL adapter peers/cgal-METHOD, sourced with $adapter (its name) and $method
# (cgal_uv's method) set: finds the compiled program cgal_uv and runs it as
#   cgal_uv --adapter $adapter $method MESH OUT      (or --help)
#
# Decisions:
# - The program is $FHR_PEERS_BIN/cgal_uv when FHR_PEERS_BIN is set, else build/peers/cgal_uv of
#   the repository, the folder above peers/ (found from $0, so the adapters run from any folder).
# - A missing program is a usage error (exit code 2, one line on stderr), never a crash.
# - exec: the adapter's exit code and signals are cgal_uv's own.
peers_dir=$(dirname -- "$0")
if [ -n "${FHR_PEERS_BIN:-}" ]; then
  cgal_uv=$FHR_PEERS_BIN/cgal_uv
else
  cgal_uv=$peers_dir/../build/peers/cgal_uv
fi
if [ ! -x "$cgal_uv" ]; then
  echo "$adapter: error: the compiled program $cgal_uv is missing (configure fhr with tests or bench on and build, or set FHR_PEERS_BIN to the folder holding cgal_uv)" >&2
  exit 2
fi
exec "$cgal_uv" --adapter "$adapter" "$method" "$@"
