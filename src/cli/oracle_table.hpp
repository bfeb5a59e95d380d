// FHR cli — the results table of `fhr oracle-fuzz` and the merge of a sharded campaign
// (spec/cli.md CLI-ORACLE-7..9). A campaign of many meshes is spread over machines by
// `--shard K/N`: shard K runs the meshes i with i mod N = K − 1, and since mesh i's recipe comes
// from (seed, i) alone, the union of the shards' rows is exactly what one unsharded run finds.
// Each run writes its rows as a table (`--table FILE`, tab-separated text), and
// `fhr oracle-fuzz --merge FILE...` checks that the tables are the N shards of one campaign and
// writes the one table an unsharded run writes, byte for byte: no time, no folder, nothing that
// depends on where or when a shard ran is in it.
//
// The format, `fhr oracle-fuzz table 1` (written by table_text, read back by read_table):
//   # fhr oracle-fuzz table 1
//   # cmd<TAB>CMD             then count, seed, family, genus-max, holes-max, components-max,
//   # ...                    timeout: the settings that decide the rows, each `# key<TAB>value`
//   # shard<TAB>K/N          1/1 for an unsharded run and for a merge
//   index<TAB>family<TAB>recipe<TAB>outcome<TAB>check<TAB>reason<TAB>smaller
//   one row per mesh of the shard, by increasing index: outcome `valid` (then check, reason and
//   smaller are `-`) or `FAILED` with the kind of failure the shrinker compares (`PARAM-8`,
//   `exit 3`, `signal 11`, `timeout`, `no output`), the reason's first line and the `fhr
//   generate` command of the shrunk recipe.
// A field never holds a tab or a line break: `\` is written `\\`, a tab `\t`, a line feed `\n`,
// a carriage return `\r`.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace fhr::cli::oracle {

/// `--shard K/N`: the meshes i with i mod N = K − 1 (1 <= K <= N).
struct Shard {
    std::uint64_t k = 1, n = 1;
    bool owns(std::uint64_t i) const { return i % n == k - 1; }
    std::string text() const { return std::to_string(k) + "/" + std::to_string(n); }
    bool operator==(const Shard&) const = default;
};

/// "K/N" with 1 <= K <= N <= 10^6. \throws InvalidInput (a usage error) otherwise.
Shard parse_shard(const std::string& text);

/// The settings that decide the rows, in the table's order: the shards of one campaign have the
/// same values (compared as written).
inline constexpr const char* setting_keys[] = {"cmd",       "count",     "seed",           "family",
                                               "genus-max", "holes-max", "components-max", "timeout",
                                               "topology",  "kind",      "faces-min"};

struct TableRow {
    std::uint64_t index = 0;
    std::string family, recipe;
    std::string check;  ///< empty when the mesh passed
    std::string reason, smaller;
    /// DIST-4, DIST-7 of the output when the oracle read it (`l2 X p99 Y max Z`), else "-".
    std::string distortion = "-";
    bool failed() const { return !check.empty(); }
};

struct Table {
    std::vector<std::string> settings;  ///< one value per setting_keys entry
    Shard shard;
    std::vector<TableRow> rows;   ///< by increasing index
    std::uint64_t count() const;  ///< the setting "count": the campaign's meshes, all shards together
};

/// The table's bytes (format above).
std::string table_text(const Table& table);

/// Reads a table written by table_text and checks it is one complete shard: the header, every
/// row well formed, the rows exactly the meshes of its shard, by increasing index.
/// \throws InvalidInput(path, line, ...) when it cannot be read or is not such a table.
Table read_table(const std::string& path);

/// The N shards' tables (any order) as the one table of the unsharded run: shard 1/1, the rows of
/// all, by index. \throws InvalidInput naming the file when a table cannot be read, when its
/// settings differ from the first table's (another seed, count, command, ...), when it is a shard
/// of another N, or a shard already given (its meshes twice); and when a shard is missing.
Table merge_tables(const std::vector<std::string>& paths);

}  // namespace fhr::cli::oracle
