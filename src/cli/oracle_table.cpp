// FHR cli — writing, reading and merging `fhr oracle-fuzz` tables (the format and why: see
// oracle_table.hpp; spec/cli.md CLI-ORACLE-7..9). Reading is strict, as everywhere in fhr: a
// table that is not exactly what table_text writes is refused with its file and line, since a
// merge that silently dropped or doubled a mesh would report a campaign that never ran.
#include "cli/oracle_table.hpp"

#include <charconv>
#include <iterator>
#include <map>

#include <fhr/core/errors.hpp>
#include <fhr/io/read.hpp>
#include "cli/common.hpp"

namespace fhr::cli::oracle {
namespace {

constexpr const char* magic = "# fhr oracle-fuzz table 1";
constexpr const char* columns = "index\tfamily\trecipe\toutcome\tcheck\treason\tsmaller\tdistortion";

std::string escape(const std::string& s) {
    std::string e;
    for (char c : s) {
        switch (c) {
            case '\\': e += "\\\\"; break;
            case '\t': e += "\\t"; break;
            case '\n': e += "\\n"; break;
            case '\r': e += "\\r"; break;
            default: e += c;
        }
    }
    return e;
}

/// The inverse of escape, or false on a `\` not followed by one of `\ t n r`.
bool unescape(const std::string& e, std::string& s) {
    s.clear();
    for (std::size_t k = 0; k < e.size(); ++k) {
        if (e[k] != '\\') {
            s += e[k];
            continue;
        }
        if (++k == e.size()) return false;
        switch (e[k]) {
            case '\\': s += '\\'; break;
            case 't': s += '\t'; break;
            case 'n': s += '\n'; break;
            case 'r': s += '\r'; break;
            default: return false;
        }
    }
    return true;
}

/// A decimal without sign or leading zeros (but "0"), the whole string.
bool parse_count(const std::string& s, std::uint64_t& value) {
    if (s.empty() || (s.size() > 1 && s[0] == '0')) return false;
    const auto [end, err] = std::from_chars(s.data(), s.data() + s.size(), value);
    return err == std::errc() && end == s.data() + s.size();
}

std::vector<std::string> split_tabs(const std::string& line) {
    std::vector<std::string> fields;
    std::size_t from = 0;
    for (std::size_t at = line.find('\t'); at != std::string::npos; at = line.find('\t', from)) {
        fields.push_back(line.substr(from, at - from));
        from = at + 1;
    }
    fields.push_back(line.substr(from));
    return fields;
}

}  // namespace

Shard parse_shard(const std::string& text) {
    const std::size_t slash = text.find('/');
    Shard s;
    if (slash == std::string::npos || !parse_count(text.substr(0, slash), s.k) ||
        !parse_count(text.substr(slash + 1), s.n) || s.k < 1 || s.k > s.n || s.n > 1'000'000)
        usage_error("--shard must be K/N with 1 <= K <= N <= 1000000 (got '" + text + "')");
    return s;
}

std::uint64_t Table::count() const {
    std::uint64_t n = 0;
    parse_count(settings.at(1), n);
    return n;
}

std::string table_text(const Table& table) {
    std::string s = std::string(magic) + "\n";
    for (std::size_t k = 0; k < std::size(setting_keys); ++k)
        s += std::string("# ") + setting_keys[k] + "\t" + escape(table.settings[k]) + "\n";
    s += "# shard\t" + table.shard.text() + "\n";
    s += std::string(columns) + "\n";
    for (const TableRow& r : table.rows) {
        s += std::to_string(r.index) + "\t" + escape(r.family) + "\t" + escape(r.recipe) + "\t";
        s += r.failed() ? "FAILED\t" + escape(r.check) + "\t" + escape(r.reason) + "\t" + escape(r.smaller)
                        : std::string("valid\t-\t-\t-");
        s += "\t" + escape(r.distortion) + "\n";
    }
    return s;
}

Table read_table(const std::string& path) {
    const std::string bytes = io::read_bytes(path);
    std::vector<std::string> lines;
    std::size_t from = 0;
    for (std::size_t at = bytes.find('\n'); at != std::string::npos; at = bytes.find('\n', from)) {
        lines.push_back(bytes.substr(from, at - from));
        from = at + 1;
    }
    if (from != bytes.size())
        throw InvalidInput(path, lines.size() + 1, "the last line does not end with a line break (a table cut short?)");
    const auto fail = [&](std::size_t line, const std::string& what) { throw InvalidInput(path, line + 1, what); };
    const std::size_t header = std::size(setting_keys) + 3;  // magic, settings, shard, columns
    if (lines.empty() || lines[0] != magic)
        fail(0, std::string("not a fhr oracle-fuzz table (the first line is not '") + magic + "')");
    if (lines.size() < header) fail(lines.size() - 1, "the header is incomplete");
    Table t;
    for (std::size_t k = 0; k < std::size(setting_keys); ++k) {
        const std::string prefix = std::string("# ") + setting_keys[k] + "\t";
        std::string value;
        if (lines[k + 1].rfind(prefix, 0) != 0 || !unescape(lines[k + 1].substr(prefix.size()), value))
            fail(k + 1, std::string("expected '# ") + setting_keys[k] + "<TAB>value'");
        t.settings.push_back(value);
    }
    std::uint64_t count = 0;
    if (!parse_count(t.settings[1], count)) fail(2, "the count is not a number");
    const std::size_t shard_line = std::size(setting_keys) + 1;
    if (lines[shard_line].rfind("# shard\t", 0) != 0) fail(shard_line, "expected '# shard<TAB>K/N'");
    try {
        t.shard = parse_shard(lines[shard_line].substr(8));
    } catch (const InvalidInput& e) {
        fail(shard_line, e.problem());
    }
    if (lines[shard_line + 1] != columns) fail(shard_line + 1, "expected the column names '" + escape(columns) + "'");
    std::uint64_t expected = t.shard.k - 1;  // the shard's meshes, in order
    for (std::size_t n = header; n < lines.size(); ++n, expected += t.shard.n) {
        const std::vector<std::string> f = split_tabs(lines[n]);
        if (f.size() != 8) fail(n, "a row has 8 tab-separated fields (got " + std::to_string(f.size()) + ")");
        TableRow r;
        if (!parse_count(f[0], r.index)) fail(n, "the index is not a number");
        if (r.index != expected)
            fail(n, "mesh " + f[0] + " where shard " + t.shard.text() + " has mesh " + std::to_string(expected) +
                        (expected < count ? "" : " (it has no more)"));
        if (expected >= count) fail(n, "mesh " + f[0] + " is beyond the count " + std::to_string(count));
        bool ok = unescape(f[1], r.family) && unescape(f[2], r.recipe) && !r.family.empty() && !r.recipe.empty();
        if (f[3] == "valid") {
            ok = ok && f[4] == "-" && f[5] == "-" && f[6] == "-";
        } else if (f[3] == "FAILED") {
            ok = ok && unescape(f[4], r.check) && unescape(f[5], r.reason) && unescape(f[6], r.smaller) &&
                 !r.check.empty();
        } else {
            fail(n, "the outcome is 'valid' or 'FAILED' (got '" + f[3] + "')");
        }
        ok = ok && unescape(f[7], r.distortion) && !r.distortion.empty();
        if (!ok) fail(n, "a malformed row (empty field, a bad escape, or '-' missing after 'valid')");
        t.rows.push_back(std::move(r));
    }
    if (expected < count)
        throw InvalidInput(
            path, 0, "shard " + t.shard.text() + " lacks mesh " + std::to_string(expected) + " (a table cut short?)");
    return t;
}

Table merge_tables(const std::vector<std::string>& paths) {
    if (paths.empty()) usage_error("--merge needs at least one table");
    std::vector<Table> tables;
    std::map<std::uint64_t, std::size_t> by_k;  // shard K -> its table in `tables` (and `paths`)
    for (const std::string& path : paths) {
        Table t = read_table(path);
        if (!tables.empty()) {
            const Table& first = tables.front();
            for (std::size_t k = 0; k < std::size(setting_keys); ++k)
                if (t.settings[k] != first.settings[k])
                    throw InvalidInput(path, 0,
                                       std::string(setting_keys[k]) + " '" + escape(t.settings[k]) + "' where " +
                                           paths[0] + " has '" + escape(first.settings[k]) +
                                           "': not the same campaign");
            if (t.shard.n != first.shard.n)
                throw InvalidInput(path, 0,
                                   "shard " + t.shard.text() + " where " + paths[0] + " is shard " +
                                       first.shard.text() + ": the shards of one campaign share N");
        }
        if (const auto [at, fresh] = by_k.emplace(t.shard.k, tables.size()); !fresh)
            throw InvalidInput(path, 0,
                               "shard " + t.shard.text() + " again (so is " + paths[at->second] +
                                   "): its meshes would be counted twice");
        tables.push_back(std::move(t));
    }
    const std::uint64_t n = tables.front().shard.n, count = tables.front().count();
    for (std::uint64_t k = 1; k <= n && k - 1 < count; ++k)
        if (!by_k.count(k))
            throw InvalidInput("shard " + std::to_string(k) + "/" + std::to_string(n) + " is missing (mesh " +
                               std::to_string(k - 1) + " is in none of the tables)");
    // Every table holds exactly its shard's rows in order (read_table), so row ⌊i/N⌋ of shard
    // (i mod N) + 1, for i = 0, 1, ..., gives every mesh once, by index.
    Table merged{tables.front().settings, Shard{}, {}};
    for (std::uint64_t i = 0; i < count; ++i) merged.rows.push_back(tables[by_k.at(i % n + 1)].rows[i / n]);
    return merged;
}

}  // namespace fhr::cli::oracle
