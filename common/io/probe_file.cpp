#include "common/io/probe_file.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/io/exact_number.hpp"

namespace tankfsi {

ProbeFile::ProbeFile(const std::filesystem::path& path, std::vector<std::string> columns, double flush_interval)
    : path_(path), columns_(std::move(columns)), flush_interval_(flush_interval),
      last_flush_time_(-std::numeric_limits<double>::infinity()),
      last_time_(-std::numeric_limits<double>::infinity()) {
  for (const auto& c : columns_)
    if (c.empty() || c.find_first_of(",\n\"") != std::string::npos || c == "time_s")
      throw std::invalid_argument("probe " + path.string() + ": bad column name '" + c + "'");
  out_.open(path_, std::ios::trunc);
  if (!out_) throw std::runtime_error("cannot create probe file '" + path_.string() + "'");
  out_ << "time_s";
  for (const auto& c : columns_) out_ << ',' << c;
  out_ << '\n';
  out_.flush();
}

void ProbeFile::append(double time, std::span<const double> values) {
  if (values.size() != columns_.size())
    throw std::invalid_argument("probe " + path_.string() + ": " + std::to_string(values.size()) +
                                " values for " + std::to_string(columns_.size()) + " columns");
  if (time < last_time_)
    throw std::invalid_argument("probe " + path_.string() + ": time " + exact_text(time) + " before " +
                                exact_text(last_time_));
  last_time_ = time;
  out_ << exact_text(time);
  for (double v : values) out_ << ',' << exact_text(v);
  out_ << '\n';
  if (time - last_flush_time_ >= flush_interval_) {
    flush();
    last_flush_time_ = time;
  }
}

void ProbeFile::flush() {
  out_.flush();
  if (!out_) throw std::runtime_error("cannot write probe file '" + path_.string() + "'");
}

}  // namespace tankfsi
