// Cases files: `gjklab query --cases FILE` reads them with experiment::read_cases_file (each
// non-blank line through experiment::parse_case_line) and prints an error line for each bad
// case with experiment::json_line.
//
// Input: the file's bytes. Properties: reading never throws for a file that exists; every
// case has non-empty clouds of finite points and finite radii >= 0; every case survives the
// round trip through case_to_json_line (same coordinates and radii, bit for bit, and the same
// line when written again); every error line is valid JSON that names the case's id.
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "gjklab/experiment/cases/cloud_io.hpp"
#include "support.hpp"

namespace {

using gjklab::Vec3;
using gjklab::experiment::CaseError;
using gjklab::experiment::PointCase;
using gjklab::fuzz::violated;

void check_cloud(const std::vector<Vec3>& cloud) {
  if (cloud.empty()) violated("a case with an empty cloud");
  for (const Vec3& p : cloud)
    if (!p.allFinite()) violated("a case with a non-finite coordinate");
}

bool same_bits(double x, double y) {
  return x == y && std::signbit(x) == std::signbit(y);
}

bool same_cloud(const std::vector<Vec3>& x, const std::vector<Vec3>& y) {
  if (x.size() != y.size()) return false;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (int k = 0; k < 3; ++k)
      if (!same_bits(x[i][k], y[i][k])) return false;
  return true;
}

void check_case(const PointCase& c) {
  check_cloud(c.a);
  check_cloud(c.b);
  if (!std::isfinite(c.radius_a) || c.radius_a < 0 || !std::isfinite(c.radius_b) || c.radius_b < 0)
    violated("a case with a radius that is not finite and >= 0");
  const std::string line = gjklab::experiment::case_to_json_line(c);
  const auto again = gjklab::experiment::parse_case_line(line, 1);
  const auto* d = std::get_if<PointCase>(&again);
  if (!d) violated("a case written by case_to_json_line does not read back");
  if (!same_cloud(c.a, d->a) || !same_cloud(c.b, d->b) || !same_bits(c.radius_a, d->radius_a) ||
      !same_bits(c.radius_b, d->radius_b))
    violated("a case changed in the round trip through case_to_json_line");
  if (gjklab::experiment::case_to_json_line(*d) != line)
    violated("case_to_json_line is not stable under a second round trip");
}

/// The error line `gjklab query` prints for a bad case.
void check_error(const CaseError& e) {
  if (e.problem.empty()) violated("a case error without a problem");
  nlohmann::ordered_json j;
  j["id"] = e.id;
  j["error"] = e.problem;
  const std::string line = gjklab::experiment::json_line(j);
  if (line.find('\n') != std::string::npos) violated("an error line spans lines");
  if (!nlohmann::json::accept(line)) violated("an error line is not valid JSON");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = gjklab::fuzz::write_scratch_file("cases.jsonl", std::span(data, size));
  for (const auto& item : gjklab::experiment::read_cases_file(path)) {
    if (const auto* c = std::get_if<PointCase>(&item))
      check_case(*c);
    else
      check_error(std::get<CaseError>(item));
  }
  return 0;
}
