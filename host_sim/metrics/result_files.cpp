#include "host_sim/metrics/result_files.hpp"

#include <charconv>
#include <fstream>
#include <string>

#include "io/input_error.hpp"

namespace irloc::sim {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields(1);
  for (const char c : line) {
    if (c == ',') {
      fields.emplace_back();
    } else if (c != '\r') {
      fields.back() += c;
    }
  }
  return fields;
}

// Lines of a CSV file after its header, which must be `header`; calls row(fields, where).
template <typename Row>
void read_csv(const std::filesystem::path& path, const std::string& header, std::size_t columns, Row row) {
  std::ifstream in(path);
  if (!in) throw io::InputError(path.string() + ": cannot open");
  std::string line;
  if (!std::getline(in, line) || split(line) != split(header)) {
    throw io::InputError(path.string() + ":1: expected the header " + header);
  }
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    const std::vector<std::string> fields = split(line);
    const std::string where = path.string() + ":" + std::to_string(number);
    if (fields.size() != columns) {
      throw io::InputError(where + ": expected " + std::to_string(columns) + " fields, got " + std::to_string(fields.size()));
    }
    row(fields, where);
  }
}

template <typename T>
T parse(const std::string& text, const std::string& where, const char* field) {
  T value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) {
    throw io::InputError(where + ": " + field + ": not a number: '" + text + "'");
  }
  return value;
}

}  // namespace

std::vector<TruthRow> read_truth_csv(const std::filesystem::path& path) {
  std::vector<TruthRow> rows;
  read_csv(path, "seq,t_ns,x,y,z,roll,pitch,yaw", 8, [&](const std::vector<std::string>& f, const std::string& where) {
    TruthRow row;
    row.seq = parse<std::uint64_t>(f[0], where, "seq");
    row.t_ns = parse<std::int64_t>(f[1], where, "t_ns");
    row.x = parse<double>(f[2], where, "x");
    row.y = parse<double>(f[3], where, "y");
    row.z = parse<double>(f[4], where, "z");
    row.roll = parse<double>(f[5], where, "roll");
    row.pitch = parse<double>(f[6], where, "pitch");
    row.yaw = parse<double>(f[7], where, "yaw");
    rows.push_back(row);
  });
  return rows;
}

std::vector<PoseEstimate> read_pose_csv(const std::filesystem::path& path) {
  std::vector<PoseEstimate> rows;
  read_csv(path, "seq,t_ns,status,x,y,z,roll,pitch,yaw,marker_id,confidence,source", 12,
           [&](const std::vector<std::string>& f, const std::string& where) {
             PoseEstimate pose;
             pose.seq = parse<std::uint64_t>(f[0], where, "seq");
             pose.t_ns = parse<std::int64_t>(f[1], where, "t_ns");
             if (f[2] != "ok" && f[2] != "none") throw io::InputError(where + ": status: expected ok or none");
             pose.ok = f[2] == "ok";
             if (pose.ok) {
               pose.x = parse<double>(f[3], where, "x");
               pose.y = parse<double>(f[4], where, "y");
               pose.z = parse<double>(f[5], where, "z");
               pose.roll = parse<double>(f[6], where, "roll");
               pose.pitch = parse<double>(f[7], where, "pitch");
               pose.yaw = parse<double>(f[8], where, "yaw");
             }
             pose.marker_id = parse<int>(f[9], where, "marker_id");
             pose.confidence = parse<double>(f[10], where, "confidence");
             bool known = false;
             for (const SourceKind source : {SourceKind::dot, SourceKind::square, SourceKind::led, SourceKind::external,
                                             SourceKind::fused}) {
               if (f[11] == to_string(source)) {
                 pose.source = source;
                 known = true;
               }
             }
             if (!known) throw io::InputError(where + ": source: unknown '" + f[11] + "'");
             rows.push_back(pose);
           });
  return rows;
}

}  // namespace irloc::sim
