#include "surface_nbv/mission/flight_csv.h"

#include <fstream>

namespace surface_nbv {

Status writeFlightCsv(const std::string& file, const std::vector<double>& t,
                      const std::vector<Eigen::Vector4d>& poses) {
  if (t.size() != poses.size()) return Status::Error(file + ": times and poses differ in number");
  std::ofstream out(file);
  out.precision(10);
  out << kFlightCsvHeader << "\n";
  for (size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Vector4d& q = poses[i];
    out << t[i] << "," << q.x() << "," << q.y() << "," << q.z() << "," << q.w() << "\n";
  }
  return out ? Status::Ok() : Status::Error("cannot write " + file);
}

}  // namespace surface_nbv
