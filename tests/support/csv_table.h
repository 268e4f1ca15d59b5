#pragma once
// A CSV file as the tools write it (bench.csv: a header line, then one row per line, commas
// only as separators) read into rows keyed by column name, and a numeric cell that must be
// there and parse whole. What the tests of the bench's tables share.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace specula::test {

using CsvRow = std::map<std::string, std::string>;
using CsvTable = std::vector<CsvRow>;

inline std::vector<std::string> splitCsvLine(const std::string& s) {
    std::vector<std::string> f;
    std::stringstream ss(s);
    std::string x;
    while (std::getline(ss, x, ','))
        f.push_back(x);
    return f;
}

// Every row of `file`; a row whose cell count differs from the header's fails the test.
inline CsvTable readCsv(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::string line;
    CsvTable rows;
    if (!std::getline(in, line)) return rows;
    const std::vector<std::string> header = splitCsvLine(line);
    while (std::getline(in, line)) {
        const std::vector<std::string> f = splitCsvLine(line);
        EXPECT_EQ(f.size(), header.size()) << line;
        CsvRow row;
        for (std::size_t i = 0; i < header.size() && i < f.size(); ++i)
            row[header[i]] = f[i];
        rows.push_back(row);
    }
    return rows;
}

// The cell `key` of `row` as a number; a missing column or a cell that is not wholly a
// number fails the test (and gives NaN).
inline double num(const CsvRow& row, const std::string& key) {
    const auto it = row.find(key);
    EXPECT_NE(it, row.end()) << "no column " << key;
    if (it == row.end()) return std::nan("");
    char* end = nullptr;
    const double v = std::strtod(it->second.c_str(), &end);
    EXPECT_TRUE(end && *end == '\0') << key << " = '" << it->second << "'";
    return v;
}

} // namespace specula::test
