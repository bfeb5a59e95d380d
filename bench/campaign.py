"""Campaigns of many independent runs, spread over machines: what `./run corpus`
(run_corpus.py) and `./run families` (run_families.py) share — the shards, the results files and
their merge. The same scheme as `fhr oracle-fuzz --shard/--merge` (src/cli/oracle_table.hpp).

A campaign is `count` items, item i decided by the campaign's parameters and i alone (a corpus
mesh by its place in the sorted list of files, a generated mesh by (seed, family, i)), never by a
stream shared between items. Shard K/N runs the items i with i mod N = K − 1, so N shards run by
GNU parallel or a Slurm job array (README, "Campaigns across machines") together run each item
once, and exactly as one unsharded run would. Within a shard, `-j J` runs J items at a time.

Each run writes its rows, by index, to a results file in its output folder: `results.json` when
unsharded, `results-K-of-N.json` for shard K/N (so shards may share a folder). The file is one
JSON object, written to a temporary name and renamed (no partial file is ever seen):
    {"format": "fhr campaign 1", "campaign": NAME, "params": {...}, "count": C, "shard": "K/N",
     "rows": [{"index": 0, ...}, ...]}
`params` are what decides the rows (shards of one campaign have equal params and count); a row's
times are under the keys TIMES only, the one thing that differs between two runs of an item.
`--merge PATH...` reads the shards' files (or the results-K-of-N.json in each folder given),
checks they are the N shards of one campaign — same campaign, params, count and N, each K once,
none missing, each complete — and gives the rows of the unsharded run; any mismatch is a
one-line error and exit code 2."""
import argparse
import concurrent.futures
import glob
import json
import os
import sys

FORMAT = "fhr campaign 1"
TIMES = ("seconds",)


class CampaignError(Exception):
    """A results file that cannot be read or merged: one line, exit code 2."""


def shard_type(text):
    """argparse type of --shard: "K/N", 1 <= K <= N, as a pair (K, N)."""
    parts = text.split("/")
    if len(parts) != 2 or not all(p.isdigit() and (p == "0" or p[0] != "0") for p in parts) \
            or not 1 <= int(parts[0]) <= int(parts[1]):
        raise argparse.ArgumentTypeError("--shard must be K/N with 1 <= K <= N (got %r)" % text)
    return int(parts[0]), int(parts[1])


def add_options(parser):
    parser.add_argument("--shard", type=shard_type, default=(1, 1), metavar="K/N",
                        help="run the items i with i mod N = K - 1 only (default 1/1: all)")
    parser.add_argument("-j", "--jobs", type=int, default=1, help="items run at a time (default 1)")
    parser.add_argument("--merge", action="store_true",
                        help="merge the shards' results (files, or folders holding results-K-of-N.json)")
    parser.add_argument("--results", metavar="FILE", help="with --merge: also write the merged results here")


def shard_text(shard):
    return "%d/%d" % shard


def results_name(shard):
    return "results.json" if shard == (1, 1) else "results-%d-of-%d.json" % shard


def run_shard(count, shard, work, jobs, describe):
    """work(i) -> row (a dict) for each item i of the shard, `jobs` at a time; one progress line
    per item on stderr as it ends (describe(row)); the rows by index."""
    indices = range(shard[0] - 1, count, shard[1])
    rows = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        futures = [pool.submit(work, i) for i in indices]
        try:
            for done, future in enumerate(concurrent.futures.as_completed(futures), 1):
                row = future.result()
                print("[%d/%d] %s" % (done, len(futures), describe(row)), file=sys.stderr, flush=True)
                rows.append(row)
        except BaseException:  # a CampaignError (or ^C): the items not started are not run
            for future in futures:
                future.cancel()
            raise
    return sorted(rows, key=lambda r: r["index"])


def write_results(path, campaign, params, count, shard, rows):
    document = {"format": FORMAT, "campaign": campaign, "params": params, "count": count,
                "shard": shard_text(shard), "rows": rows}
    temporary = "%s.tmp-%d" % (path, os.getpid())
    with open(temporary, "w") as f:
        json.dump(document, f, indent=1, sort_keys=True)
        f.write("\n")
    os.replace(temporary, path)


def read_results(path, campaign):
    """One shard's results, checked complete: its rows are exactly its items, by index."""
    try:
        with open(path) as f:
            d = json.load(f)
    except (OSError, ValueError) as e:
        raise CampaignError("%s: cannot read: %s" % (path, e))
    if not isinstance(d, dict) or d.get("format") != FORMAT:
        raise CampaignError("%s: not a results file (no \"format\": \"%s\")" % (path, FORMAT))
    if d.get("campaign") != campaign:
        raise CampaignError("%s: results of `%s`, not of `%s`" % (path, d.get("campaign"), campaign))
    try:
        d["shard"] = shard_type(d["shard"])
        expected = list(range(d["shard"][0] - 1, d["count"], d["shard"][1]))
        indices = [r["index"] for r in d["rows"]]
    except (KeyError, TypeError, argparse.ArgumentTypeError) as e:
        raise CampaignError("%s: a malformed results file (%s)" % (path, e))
    if indices != expected:
        missing = sorted(set(expected) - set(indices))
        raise CampaignError("%s: shard %s has not exactly its items (%s)" % (
            path, shard_text(d["shard"]), "lacks item %d" % missing[0] if missing else "items out of place"))
    return d


def expand(paths):
    """The files named, and the results-K-of-N.json in each folder named."""
    files = []
    for p in paths:
        if os.path.isdir(p):
            found = sorted(glob.glob(os.path.join(p, "results-*-of-*.json")))
            if not found:
                raise CampaignError("%s: no results-K-of-N.json in this folder" % p)
            files += found
        else:
            files.append(p)
    return files


def merge(paths, campaign):
    """The shards' results as the unsharded run's: (params, count, rows by index)."""
    files = expand(paths)
    if not files:
        raise CampaignError("--merge needs results files or folders")
    shards = {}  # K -> (file, results)
    first_file, first = files[0], None
    for path in files:
        d = read_results(path, campaign)
        if first is None:
            first = d
        elif d["params"] != first["params"] or d["count"] != first["count"]:
            key = next((k for k in sorted(set(d["params"]) | set(first["params"]))
                        if d["params"].get(k) != first["params"].get(k)), "count")
            mine = d["params"].get(key) if key != "count" else d["count"]
            theirs = first["params"].get(key) if key != "count" else first["count"]
            raise CampaignError("%s: %s %s where %s has %s: not the same campaign" % (
                path, key, json.dumps(mine), first_file, json.dumps(theirs)))
        elif d["shard"][1] != first["shard"][1]:
            raise CampaignError("%s: shard %s where %s is shard %s: the shards of one campaign share N" % (
                path, shard_text(d["shard"]), first_file, shard_text(first["shard"])))
        k = d["shard"][0]
        if k in shards:
            raise CampaignError("%s: shard %s again (so is %s): its items would be counted twice" % (
                path, shard_text(d["shard"]), shards[k][0]))
        shards[k] = (path, d)
    n, count = first["shard"][1], first["count"]
    for k in range(1, min(n, count) + 1):
        if k not in shards:
            raise CampaignError("shard %d/%d is missing (item %d is in none of the results)" % (k, n, k - 1))
    rows = sorted((r for _, d in shards.values() for r in d["rows"]), key=lambda r: r["index"])
    return first["params"], count, rows


def main(campaign, options, paths, start, describe, report):
    """The flow both scripts share. Merge: `paths` are results; run: start() -> (params, count,
    work, out_dir) sets the campaign up, then the shard runs and writes its results. Either way
    report(rows) prints the table and returns the exit code."""
    try:
        if options.merge:
            params, count, rows = merge(paths, campaign)
            if options.results:
                write_results(options.results, campaign, params, count, (1, 1), rows)
        else:
            params, count, work, out_dir = start()
            rows = run_shard(count, options.shard, work, options.jobs, describe)
            write_results(os.path.join(out_dir, results_name(options.shard)), campaign, params, count,
                          options.shard, rows)
    except CampaignError as e:
        print("%s: error: %s" % (os.path.basename(sys.argv[0]), e), file=sys.stderr)
        sys.exit(2)
    sys.exit(report(rows))
