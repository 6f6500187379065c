#include "jgm_laws.h"
#include "jgm_tangential.h"

#include "comm.h"
#include "error.h"
#include "fastrest_law.h"
#include "pointers.h"
#include "utils.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <mpi.h>
#include <sstream>
#include <unistd.h>

#ifndef FASTREST_PYTHON
#define FASTREST_PYTHON "python3"
#endif

using namespace LAMMPS_NS;

namespace FastrestJGM {

// the law file's layout: jgm_law_file.h, generated from fastrest.lammps.laws
using LawFile::ROW;
using LawFile::AREA_ROW;
using LawFile::MAX_LAWS;

static std::string shell_quote(const std::string &s)
{
  std::string q = "'";
  for (char c : s) {
    if (c == '\'') q += "'\\''";
    else q += c;
  }
  return q + "'";
}

static std::string read_file(const std::string &path, std::vector<char> *bytes)
{
  std::ifstream in(path, std::ios::binary);
  if (!in) return "cannot open " + path;
  std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  *bytes = data;
  return "";
}

std::string parse_laws(const std::vector<char> &bytes, size_t expected, Laws &out)
{
  out.rows.clear();
  out.area.clear();
  out.law.clear();
  const size_t head = LawFile::MAGIC_SIZE;
  if (bytes.size() < head + 8 || std::memcmp(bytes.data(), LawFile::MAGIC, head) != 0 || (bytes.size() - head) % 8 != 0)
    return "not a fastrest law file";
  size_t nd = (bytes.size() - head) / 8;
  std::vector<double> d(nd);
  std::memcpy(d.data(), bytes.data() + head, nd * 8);
  double n = d[0];
  if (!(n == static_cast<double>(expected))) return "law file holds another number of laws";
  size_t at = 1;
  for (size_t k = 0; k < expected; ++k) {
    if (at + LawFile::HEAD > nd) return "law file truncated";
    Law law;
    law.omega_c1 = d[at + LawFile::OMEGA_C1];
    law.p_c1 = d[at + LawFile::P_C1];
    law.w_end = d[at + LawFile::W_END];
    double nrows = d[at + LawFile::ROWS];
    law.a_c1 = d[at + LawFile::A_C1];
    law.g_eff = d[at + LawFile::G_EFF];
    at += LawFile::HEAD;
    for (double v : {law.omega_c1, law.p_c1, law.w_end, law.a_c1, law.g_eff})
      if (!(v > 0.0) || !std::isfinite(v)) return "law file holds a critical value that is not finite and > 0";
    if (!(nrows >= 1.0) || nrows != std::floor(nrows) || nrows * (ROW + AREA_ROW) > static_cast<double>(nd - at))
      return "law file holds a bad row count";
    size_t nr = static_cast<size_t>(nrows);
    law.first = static_cast<int64_t>(out.rows.size() / ROW);
    law.last = static_cast<int64_t>(nr) - 1;
    for (size_t m = 0; m < nr * ROW; ++m) {
      if (!std::isfinite(d[at + m])) return "law file holds a row value that is not finite";
      out.rows.push_back(d[at + m]);
    }
    at += nr * ROW;
    for (size_t m = 0; m < nr * AREA_ROW; ++m) {
      if (!std::isfinite(d[at + m])) return "law file holds an area value that is not finite";
      out.area.push_back(d[at + m]);
    }
    at += nr * AREA_ROW;
    out.law.push_back(law);
  }
  if (at != nd) return "law file has trailing data";
  return "";
}

double finite_number(LAMMPS *lmp, const std::string &where, const char *what, const char *text)
{
  double v = utils::numeric(FLERR, text, false, lmp);
  if (!std::isfinite(v)) lmp->error->all(FLERR, "{}: {} = {} is not finite", where, what, text);
  return v;
}

Body read_body(LAMMPS *lmp, const std::string &where, const char *E, const char *nu, const char *Sy, const char *Et)
{
  Body b;
  b.E = finite_number(lmp, where, "E", E);
  b.nu = finite_number(lmp, where, "nu", nu);
  b.Sy = finite_number(lmp, where, "Sy", Sy);
  b.Et = Et ? finite_number(lmp, where, "Et", Et) : 0.0;
  Error *error = lmp->error;
  if (!(b.E > 0.0)) error->all(FLERR, "{}: E = {} must be > 0", where, E);
  if (!(b.nu >= 0.0 && b.nu < 0.5)) error->all(FLERR, "{}: nu = {} must be in [0, 0.5)", where, nu);
  if (!(b.Sy > 0.0)) error->all(FLERR, "{}: Sy = {} must be > 0", where, Sy);
  if (!(b.Et >= 0.0 && b.Et < b.E)) error->all(FLERR, "{}: Et = {} must be in [0, E = {})", where, Et, E);
  return b;
}

double pascal_per_unit(const char *units)
{
  std::string u = units ? units : "";
  if (u == "si") return 1.0;
  if (u == "cgs") return 0.1;       // dyne/cm^2
  if (u == "micro") return 1e3;     // picogram/(micrometer microsecond^2)
  if (u == "nano") return 1e6;      // attogram/(nanometer nanosecond^2)
  return 0.0;
}

int unloading_index(const std::string &model)
{
  if (model == "jcg") return 0;
  if (model == "etsion") return 1;
  if (model == "brake") return 2;
  return -1;
}

std::string row_problem(const Laws &laws, int k, const double *state)
{
  if (k < 0 || k >= static_cast<int>(laws.law.size())) return "no law for the pair";
  const Law &law = laws.law[k];
  for (int m = 0; m < STATE; ++m)
    if (!std::isfinite(state[m])) return "a value is not finite";
  if (!(state[0] > 0.0 && state[0] <= law.w_end))
    return fmt::format("w_max* = {:.17g} is not in (0, {:.17g}], the law's domain", state[0], law.w_end);
  double fresh[STATE] = {0.0, 0.0, 0.0, 0.0};
  fastrest_law_step(laws.rows.data(), law.first, law.last, law.w_end, fresh, state[0]);
  // the same law and w_max give the same row; 1e-9 leaves room for another compiler's rounding
  const char *names[STATE] = {"w_max*", "P*(w_max)", "w_res*", "delta"};
  for (int m = 1; m < STATE; ++m) {
    double scale = m == 1 ? std::fabs(fresh[m]) : std::max(1.0, state[0]);
    if (!(std::fabs(state[m] - fresh[m]) <= 1e-9 * scale))
      return fmt::format("{} = {:.17g} where the law gives {:.17g} at w_max* = {:.17g}", names[m], state[m], fresh[m],
                         state[0]);
  }
  return "";
}

void request_laws(LAMMPS *lmp, const std::vector<LawRequest> &requests, const std::string &unloading,
                  double pascal, Laws &out)
{
  if (requests.size() > MAX_LAWS)
    lmp->error->all(FLERR, "{} distinct material pairs need a contact law each; fastrest builds at most {} in one "
                           "run: give types that share a material identical coefficients (they share one law)",
                    requests.size(), MAX_LAWS);
  std::string message;
  std::vector<char> bytes;
  if (lmp->comm->me == 0) {
    const char *tmp = std::getenv("TMPDIR");
    std::string templ = std::string(tmp && *tmp ? tmp : "/tmp") + "/fastrest-jgm-XXXXXX";
    std::vector<char> dir(templ.begin(), templ.end());
    dir.push_back('\0');
    if (!mkdtemp(dir.data())) {
      message = "cannot make a temporary folder under " + templ;
    } else {
      std::string d(dir.data());
      std::string req = d + "/request.txt", bin = d + "/laws.bin", err = d + "/stderr.txt";
      {
        std::ofstream f(req);
        f.precision(17);
        for (const auto &r : requests)
          f << (r.flat ? "flat" : "spheres") << ' ' << r.a.E << ' ' << r.a.nu << ' ' << r.a.Sy << ' '
            << r.a.Et << ' ' << r.b.E << ' ' << r.b.nu << ' ' << r.b.Sy << ' ' << r.b.Et << ' '
            << r.label << '\n';
      }
      const char *py = std::getenv("FASTREST_PYTHON");
      std::string python = (py && *py) ? py : FASTREST_PYTHON;
      std::string cmd = shell_quote(python) + " -m fastrest lammps law --unloading " +
          shell_quote(unloading) + " --pascal " + fmt::format("{:.17g}", pascal) + " --request " + shell_quote(req) + " --out " + shell_quote(bin) +
          " 2> " + shell_quote(err) + " < /dev/null > /dev/null";
      int rc = std::system(cmd.c_str());
      if (rc != 0) {
        std::vector<char> e;
        read_file(err, &e);
        std::string text(e.begin(), e.end());
        // the last line of a Python error is its message
        while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
        size_t nl = text.rfind('\n');
        std::string last = nl == std::string::npos ? text : text.substr(nl + 1);
        if (last.empty()) last = "exit status " + std::to_string(rc) + " and no message";
        message = "fastrest (" + python + " -m fastrest lammps law) failed: " + last;
      } else {
        message = read_file(bin, &bytes);
        std::vector<char> e;
        read_file(err, &e);
        std::istringstream lines(std::string(e.begin(), e.end()));
        std::string line;
        while (std::getline(lines, line))    // fastrest's warnings (ValidityWarning ...) go to the log
          if (line.rfind("fastrest", 0) == 0) lmp->error->warning(FLERR, line);
      }
      std::remove(req.c_str());
      std::remove(bin.c_str());
      std::remove(err.c_str());
      rmdir(d.c_str());
    }
  }
  long sizes[2] = {static_cast<long>(message.size()), static_cast<long>(bytes.size())};
  MPI_Bcast(sizes, 2, MPI_LONG, 0, lmp->world);
  message.resize(sizes[0]);
  bytes.resize(sizes[1]);
  if (sizes[0]) MPI_Bcast(&message[0], static_cast<int>(sizes[0]), MPI_CHAR, 0, lmp->world);
  if (message.empty() && sizes[1])
    MPI_Bcast(bytes.data(), static_cast<int>(sizes[1]), MPI_CHAR, 0, lmp->world);
  if (message.empty()) message = parse_laws(bytes, requests.size(), out);
  if (!message.empty()) lmp->error->all(FLERR, message);
}

int read_resistance(LAMMPS *lmp, const std::string &where, int narg, char **arg, int k, Resistance &res)
{
  std::string key = arg[k];
  if (k + 1 >= narg) lmp->error->all(FLERR, "{}: '{}' needs a model: none or sds K GAMMA MU{}", where, key,
                                     key == "twisting" ? " or marshall" : "");
  std::string model = arg[k + 1];
  if (model == "none") {
    if (key == "rolling") res.roll_k = -1.0;
    else res.twist = Resistance::NONE;
    return k + 2;
  }
  if (model == "marshall" && key == "twisting") {
    res.twist = Resistance::MARSHALL;
    return k + 2;
  }
  if (model != "sds")
    lmp->error->all(FLERR, "{}: {} model '{}' is not one of none, sds{}", where, key, model,
                    key == "twisting" ? ", marshall" : "");
  if (k + 4 >= narg) lmp->error->all(FLERR, "{}: '{} sds' needs K GAMMA MU", where, key);
  const char *names[3] = {"K", "GAMMA", "MU"};
  double v[3];
  for (int m = 0; m < 3; ++m) {
    v[m] = finite_number(lmp, where, fmt::format("{} {}", key, names[m]).c_str(), arg[k + 2 + m]);
    if (!(v[m] >= 0.0)) lmp->error->all(FLERR, "{}: {} {} = {} must be >= 0", where, key, names[m], arg[k + 2 + m]);
  }
  if (key == "rolling") {
    res.roll_k = v[0];
    res.roll_gamma = v[1];
    res.roll_mu = v[2];
  } else {
    res.twist = Resistance::SDS;
    res.twist_k = v[0];
    res.twist_gamma = v[1];
    res.twist_mu = v[2];
  }
  return k + 5;
}

}    // namespace FastrestJGM
