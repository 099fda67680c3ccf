// Times CGAL's Delaunay_triangulation_3 (Epick kernel) on a points file: one "x y z" per
// line. Prints points, finite cells, wall ms and CPU ms (of the whole process, so all
// threads) of the insertion by range (which includes CGAL's own spatial sort), and the
// peak RSS increase.
//
// `delaunay_cgal POINTS.xyz` is sequential; `delaunay_cgal POINTS.xyz --parallel` uses
// CGAL's parallel insertion (Parallel_tag, TBB, a 50^3 lock grid over the points' box) on
// every core TBB sees.
//
// Build: g++ -O3 -DNDEBUG -DCGAL_LINKED_WITH_TBB -o delaunay_cgal delaunay_cgal.cpp
//        -lgmp -lmpfr -ltbb
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Triangulation_data_structure_3.h>
#include <CGAL/Triangulation_vertex_base_3.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Delaunay_triangulation_3<K> DT;
typedef CGAL::Triangulation_data_structure_3<CGAL::Triangulation_vertex_base_3<K>,
                                             CGAL::Delaunay_triangulation_cell_base_3<K>,
                                             CGAL::Parallel_tag>
    ParallelTds;
typedef CGAL::Delaunay_triangulation_3<K, ParallelTds> ParallelDT;
typedef K::Point_3 Point;

static long status_kb(const char *key) {
  std::ifstream f("/proc/self/status");
  std::string line;
  size_t n = std::string(key).size();
  while (std::getline(f, line))
    if (line.compare(0, n, key) == 0) return std::stol(line.substr(n));
  return 0;
}

int main(int argc, char **argv) {
  if (argc < 2) {
    std::cerr << "usage: delaunay_cgal POINTS.xyz\n";
    return 2;
  }
  std::ifstream in(argv[1]);
  std::vector<Point> pts;
  double x, y, z;
  while (in >> x >> y >> z) pts.emplace_back(x, y, z);
  bool parallel = argc > 2 && std::string(argv[2]) == "--parallel";
  CGAL::Bbox_3 box;
  for (const Point &p : pts) box += p.bbox();
  { std::ofstream r("/proc/self/clear_refs"); r << "5"; }
  long before = status_kb("VmRSS:");
  std::clock_t c0 = std::clock();
  auto t0 = std::chrono::steady_clock::now();
  size_t cells;
  if (parallel) {
    ParallelDT::Lock_data_structure locks(box, 50);
    ParallelDT dt(pts.begin(), pts.end(), &locks);
    cells = dt.number_of_finite_cells();
  } else {
    DT dt(pts.begin(), pts.end());
    cells = dt.number_of_finite_cells();
  }
  auto t1 = std::chrono::steady_clock::now();
  std::clock_t c1 = std::clock();
  long peak = status_kb("VmHWM:");
  double ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
  double cpu = 1000.0 * double(c1 - c0) / CLOCKS_PER_SEC;
  std::printf("cgal%s %zu points %zu tets %.1f ms wall %.1f ms cpu peak +%.1f B/pt\n",
              parallel ? "-parallel" : "", pts.size(), cells, ms, cpu,
              (peak - before) * 1024.0 / pts.size());
  return 0;
}
