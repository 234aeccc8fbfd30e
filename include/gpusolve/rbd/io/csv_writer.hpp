// CsvWriter: writes one table (per-step statistics) as comma-separated values with a header row.
#pragma once

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "gpusolve/core/error.hpp"

namespace gpusolve::rbd::io {

// Every row must have as many values as the header has columns: a short or long
// row is a bug in the caller and throws instead of shifting columns silently.
// Values are written with 10 significant digits; non-finite ones as nan/inf/-inf,
// which Python's float() and most plotting tools read back.
class CsvWriter {
 public:
  CsvWriter(const std::string& path, std::vector<std::string> columns)
      : out_(path), columns_(std::move(columns)) {
    if (!out_) throw InvalidArgumentError("CsvWriter: cannot open '" + path + "' for writing");
    if (columns_.empty()) throw InvalidArgumentError("CsvWriter: no columns");
    for (std::size_t i = 0; i < columns_.size(); ++i) {
      if (columns_[i].find_first_of(",\"\n") != std::string::npos)
        throw InvalidArgumentError("CsvWriter: column name '" + columns_[i] + "' needs quoting");
      out_ << (i ? "," : "") << columns_[i];
    }
    out_ << '\n';
  }

  void row(const std::vector<double>& values) {
    if (values.size() != columns_.size())
      throw SizeMismatchError("CsvWriter: row has " + std::to_string(values.size()) +
                              " values, header has " + std::to_string(columns_.size()));
    for (std::size_t i = 0; i < values.size(); ++i) out_ << (i ? "," : "") << format(values[i]);
    out_ << '\n';
    ++rows_;
  }

  const std::vector<std::string>& columns() const { return columns_; }
  std::size_t rows() const { return rows_; }
  void flush() { out_.flush(); }

  static std::string format(double v) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
  }

 private:
  std::ofstream out_;
  std::vector<std::string> columns_;
  std::size_t rows_ = 0;
};

}  // namespace gpusolve::rbd::io
