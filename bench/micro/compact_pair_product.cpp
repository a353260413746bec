// Stand-alone measurement (not built by CMake): the CG product of a sphere-pair matrix with dense 6x6
// off-diagonal blocks (Eigen) against the same blocks kept as their 9 numbers and applied with dot and
// cross products (LubricationPair::centred_gram's ij block). bench/README.md, "Sweep direction and
// prefetching", last paragraph.  g++ -O2 -std=c++20 -I/usr/include/eigen3 compact_pair_product.cpp && ./a.out
// 64000
#include <Eigen/Dense>
#include <chrono>
#include <cstdio>
#include <random>
#include <vector>
using Mat6 = Eigen::Matrix<double, 6, 6>;
using V3 = Eigen::Vector3d;
struct Pair {
  double d[3];
  double sq, sh, pu, tw, li, lj;
};                                     // 9 numbers (+1)
static Mat6 block_of(const Pair& p) {  // the ij block of centred_gram
  V3 d(p.d[0], p.d[1], p.d[2]);
  Eigen::Matrix3d dd = d * d.transpose(), P = Eigen::Matrix3d::Identity() - dd, D;
  D << 0, -d[2], d[1], d[2], 0, -d[0], -d[1], d[0], 0;
  Mat6 ij;
  ij.topLeftCorner<3, 3>() = -(p.sq * dd + p.sh * P);
  ij.topRightCorner<3, 3>() = -(p.sh * p.lj) * D;
  ij.bottomLeftCorner<3, 3>() = -(p.sh * p.li) * D;
  ij.bottomRightCorner<3, 3>() = (p.sh * p.li * p.lj - p.pu) * P - p.tw * dd;
  return ij;
}
int main(int argc, char** argv) {
  int n = atoi(argv[1]);
  int per = 2;
  std::mt19937 g(1);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<int> I, J;
  for (int i = 0; i < n; ++i)
    for (int k = 1; k <= per; ++k) {
      I.push_back(i);
      J.push_back((i + k * 37) % n);
    }
  size_t m = I.size();
  std::vector<Pair> P(m);
  std::vector<Mat6> B(m), Dg(n);
  for (size_t k = 0; k < m; ++k) {
    V3 d(u(g), u(g), u(g));
    d.normalize();
    P[k] = {{d[0], d[1], d[2]}, 1 + u(g), 1 + u(g), 1 + u(g), 1 + u(g), 1, 1};
    B[k] = block_of(P[k]);
  }
  for (int i = 0; i < n; ++i) Dg[i] = Mat6::Identity() * 10;
  std::vector<double> x(6 * n), y(6 * n), y2(6 * n);
  for (auto& v : x) v = u(g);
  auto diagonal_part = [&](std::vector<double>& out) {  // out = diag(A) x, the same in both forms
    std::fill(out.begin(), out.end(), 0.0);
    for (int i = 0; i < n; ++i)
      Eigen::Map<Eigen::Matrix<double, 6, 1>>(&out[6 * i]) +=
          Dg[i] * Eigen::Map<const Eigen::Matrix<double, 6, 1>>(&x[6 * i]);
  };
  auto dense = [&] {
    diagonal_part(y);
    for (size_t k = 0; k < m; ++k) {
      int i = I[k], j = J[k];
      Eigen::Map<Eigen::Matrix<double, 6, 1>> yi(&y[6 * i]), yj(&y[6 * j]);
      Eigen::Map<const Eigen::Matrix<double, 6, 1>> xi(&x[6 * i]), xj(&x[6 * j]);
      yi.noalias() += B[k] * xj;
      yj.noalias() += B[k].transpose() * xi;
    }
  };
  auto compact = [&] {
    diagonal_part(y2);
    for (size_t k = 0; k < m; ++k) {
      const Pair& p = P[k];
      int i = I[k], j = J[k];
      V3 d(p.d[0], p.d[1], p.d[2]);
      V3 ui(&x[6 * i]), wi(&x[6 * i + 3]), uj(&x[6 * j]), wj(&x[6 * j + 3]);
      // y_i += ij * x_j ; y_j += ij^T x_i
      double duj = d.dot(uj), dwj = d.dot(wj), dui = d.dot(ui), dwi = d.dot(wi);
      V3 Puj = uj - duj * d, Pwj = wj - dwj * d, Pui = ui - dui * d, Pwi = wi - dwi * d;
      V3 Dwj = d.cross(wj), Duj = d.cross(uj), Dwi = d.cross(wi), Dui = d.cross(ui);
      double c = p.sh * p.li * p.lj - p.pu;
      V3 fi = -(p.sq * duj * d + p.sh * Puj) - (p.sh * p.lj) * Dwj;
      V3 ti = -(p.sh * p.li) * Duj + c * Pwj - (p.tw * dwj) * d;
      V3 fj = -(p.sq * dui * d + p.sh * Pui) + (p.sh * p.li) * Dwi;  // (-(sh li) D)^T = (sh li) D
      V3 tj = (p.sh * p.lj) * Dui + c * Pwi - (p.tw * dwi) * d;
      Eigen::Map<V3>(&y2[6 * i]) += fi;
      Eigen::Map<V3>(&y2[6 * i + 3]) += ti;
      Eigen::Map<V3>(&y2[6 * j]) += fj;
      Eigen::Map<V3>(&y2[6 * j + 3]) += tj;
    }
  };
  dense();
  compact();
  double err = 0;
  for (int k = 0; k < 6 * n; ++k) err = std::max(err, std::abs(y[k] - y2[k]));
  auto time = [&](auto f) {
    double best = 1e9;
    for (int r = 0; r < 7; ++r) {
      auto t0 = std::chrono::steady_clock::now();
      for (int q = 0; q < (n < 5000 ? 200 : 5); ++q) f();
      double t =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / (n < 5000 ? 200 : 5);
      best = std::min(best, t);
    }
    return best;
  };
  double td = time(dense), tc = time(compact);
  printf("n=%d pairs=%zu dense %.3f ms compact %.3f ms ratio %.2f maxdiff %.1e\n", n, m, td * 1e3, tc * 1e3,
         tc / td, err);
}
