// Catch2 main for MPI tests: every rank runs every test case; rank 0 prints the
// report, other ranks keep theirs and print it only if they failed, so a
// failure on any rank is seen. The exit status is the worst over all ranks.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>
#include <mpi.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "common/parallel/mpi_session.hpp"

int main(int argc, char** argv) {
  int exit_status = 0;
  {
    tankfsi::MpiSession session({argv[0]});
    Catch::Session catch_session;
    if (const int rc = catch_session.applyCommandLine(argc, argv); rc != 0) return rc;
    std::string report_file;
    if (session.rank() != 0) {
      report_file = "catch_rank" + std::to_string(session.rank()) + "_" + std::to_string(getpid()) + ".txt";
      catch_session.configData().outputFilename = report_file;
    }
    const int failures = catch_session.run();
    if (session.rank() != 0) {
      if (failures != 0) {
        std::ifstream report(report_file);
        std::cerr << "---- report of rank " << session.rank() << " ----\n" << report.rdbuf();
      }
      std::remove(report_file.c_str());
    }
    int local = failures != 0 ? 1 : 0;
    MPI_Allreduce(&local, &exit_status, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  }
  return exit_status;
}
