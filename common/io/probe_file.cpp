#include "common/io/probe_file.hpp"

#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "common/io/exact_number.hpp"
#include "common/run/run_folder.hpp"

namespace tankfsi {

ProbeFile::ProbeFile(const std::filesystem::path& path, std::vector<std::string> columns, double flush_interval)
    : path_(path), columns_(std::move(columns)), flush_interval_(flush_interval),
      last_flush_time_(-std::numeric_limits<double>::infinity()),
      last_time_(-std::numeric_limits<double>::infinity()) {
  check_columns();
  out_.open(path_, std::ios::trunc);
  if (!out_) throw std::runtime_error("cannot create probe file '" + path_.string() + "'");
  out_ << header() << '\n';
  out_.flush();
}

ProbeFile::ProbeFile(const std::filesystem::path& path, std::vector<std::string> columns, double flush_interval,
                     double resume_time)
    : path_(path), columns_(std::move(columns)), flush_interval_(flush_interval), last_flush_time_(resume_time),
      last_time_(resume_time) {
  check_columns();
  std::ifstream in(path_);
  std::string line;
  if (!in || !std::getline(in, line))
    throw std::runtime_error("cannot continue probe file '" + path_.string() + "': it is missing or empty");
  if (line != header())
    throw std::runtime_error("cannot continue probe file '" + path_.string() + "': its header is '" + line +
                             "', not '" + header() + "'");
  // Times are written exactly (exact_text), so a row of the checkpoint's time
  // reads back as that very double.
  std::string kept = line + '\n';
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const double time = std::strtod(line.c_str(), nullptr);
    if (!(time <= resume_time)) break;
    kept += line + '\n';
  }
  in.close();
  write_file_atomically(path_, kept);
  out_.open(path_, std::ios::app);
  if (!out_) throw std::runtime_error("cannot open probe file '" + path_.string() + "'");
}

std::unique_ptr<ProbeFile> open_probe_file(const std::filesystem::path& path, std::vector<std::string> columns,
                                           double flush_interval, std::optional<double> resume_time) {
  if (resume_time) return std::make_unique<ProbeFile>(path, std::move(columns), flush_interval, *resume_time);
  return std::make_unique<ProbeFile>(path, std::move(columns), flush_interval);
}

void ProbeFile::check_columns() const {
  for (const auto& c : columns_)
    if (c.empty() || c.find_first_of(",\n\"") != std::string::npos || c == "time_s")
      throw std::invalid_argument("probe " + path_.string() + ": bad column name '" + c + "'");
}

std::string ProbeFile::header() const {
  std::string text = "time_s";
  for (const auto& c : columns_) text += ',' + c;
  return text;
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
