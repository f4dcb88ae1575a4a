// ripple-robustness: runs the robustness matrix (stiff and extreme inputs) through the Ripple ANARI device
// and prints one Markdown table row per case; docs/robustness.md keeps the last table.
#include "apps/ripple-robustness/Robustness.h"
#include "io/FileWrite.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace ripple::robustness {
namespace {

struct Group {
    const char* name;
    std::function<std::vector<Row>(Harness&, bool)> run;
};

const std::vector<Group>& groups() {
    static const std::vector<Group> all = {
        {"precision", precisionCases},     {"intersection", intersectionCases}, {"radiometry", radiometryCases},
        {"sizes", extremeSizeCases},       {"bad-data", badDataCases},
        {"misuse", misuseCases},
    };
    return all;
}

// A table cell: '|' escaped, line breaks as spaces.
std::string cell(const std::string& text) {
    std::string escaped;
    for (char c : text) {
        if (c == '|') escaped += "\\|";
        else escaped += c == '\n' ? ' ' : c;
    }
    return escaped;
}

std::string verdict(const Row& row) {
    if (!row.finite) return "FAIL (NaN/Inf)";
    if (row.holds) return "holds";
    return row.expected ? "FAIL" : "does not hold (expected)";
}

void writeTable(std::ostream& out, const std::vector<Row>& rows) {
    out << "| group | case | result | measured | why |\n|---|---|---|---|---|\n";
    for (const Row& r : rows)
        out << "| " << cell(r.group) << " | " << cell(r.name) << " | " << verdict(r) << " | " << cell(r.measured)
            << " | " << cell(r.why) << " |\n";
}

}  // namespace
}  // namespace ripple::robustness

int main(int argc, char** argv) {
    using namespace ripple::robustness;
    bool quick = false;
    std::vector<std::string> only;
    std::string output;
    CLI::App app{"ripple-robustness: render stiff and extreme inputs through the Ripple ANARI device and print "
                 "what holds (a Markdown table; exit status 1 when a case fails where it should hold)"};
    app.add_flag("--quick", quick, "the small sweep the tests run, instead of the full one");
    std::string names;
    for (const Group& g : groups()) names += std::string(names.empty() ? "" : ", ") + g.name;
    app.add_option("--group", only, "run only these groups: " + names);
    app.add_option("-o,--output", output, "also write the table to this file");
    CLI11_PARSE(app, argc, argv);
    for (const std::string& name : only) {
        bool known = false;
        for (const Group& g : groups()) known = known || name == g.name;
        if (!known) {
            std::fprintf(stderr, "[ripple-robustness] ERROR: unknown group '%s' (groups: %s)\n", name.c_str(), names.c_str());
            return 2;
        }
    }

    try {
        Harness harness;
        std::vector<Row> rows;
        size_t emptyGroups = 0;
        for (const Group& g : groups()) {
            if (!only.empty() && std::find(only.begin(), only.end(), g.name) == only.end()) continue;
            const auto start = std::chrono::steady_clock::now();
            std::vector<Row> groupRows = g.run(harness, quick);
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            std::fprintf(stderr, "[ripple-robustness] %s: %zu cases in %.1f s\n", g.name, groupRows.size(), seconds);
            if (groupRows.empty()) {  // a group that checks nothing is a failure, not a pass
                std::fprintf(stderr, "[ripple-robustness] ERROR: group %s produced no cases\n", g.name);
                ++emptyGroups;
            }
            rows.insert(rows.end(), groupRows.begin(), groupRows.end());
        }
        writeTable(std::cout, rows);
        if (!output.empty()) {
            std::ostringstream table;
            writeTable(table, rows);
            ripple::apps::writeFileAtomically(output, table.str(), "the table");
        }
        size_t failures = 0, precisionEnds = 0;
        for (const Row& r : rows) {
            failures += (!r.finite || (r.expected && !r.holds)) ? 1 : 0;
            precisionEnds += (r.finite && !r.expected && !r.holds) ? 1 : 0;
        }
        std::fprintf(stderr, "[ripple-robustness] %zu cases: %zu hold, %zu fail where precision ends (expected), %zu FAIL\n",
                     rows.size(), rows.size() - failures - precisionEnds, precisionEnds, failures);
        return failures == 0 && emptyGroups == 0 ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "[ripple-robustness] ERROR: %s\n", e.what());
        return 1;
    }
}
