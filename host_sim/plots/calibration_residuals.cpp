#include "host_sim/plots/calibration_residuals.hpp"

#include <cstdio>
#include <fstream>
#include <string>

#include "io/input_error.hpp"

namespace irloc::sim {

std::vector<DotResidualRow> read_calibration_residuals(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  if (!in) throw io::InputError(csv.string() + ": cannot open");
  std::string line;
  const std::string header = "u,v,before_du,before_dv,after_du,after_dv";
  if (!std::getline(in, line) || line != header) throw io::InputError(csv.string() + ":1: expected the header " + header);
  std::vector<DotResidualRow> rows;
  for (int number = 2; std::getline(in, line); ++number) {
    DotResidualRow row;
    char end = 0;
    if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf%c", &row.pixel.x(), &row.pixel.y(), &row.before.x(),
                    &row.before.y(), &row.after.x(), &row.after.y(), &end) != 6) {
      throw io::InputError(csv.string() + ":" + std::to_string(number) + ": expected six numbers");
    }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace irloc::sim
