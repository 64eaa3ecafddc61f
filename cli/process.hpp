// Running another program and collecting what it prints: the Slurm commands (study_command.cpp),
// python3 for the figures (figures.cpp).
#pragma once
#include <string>
#include <vector>

namespace passim {

// What a program printed and how it ended.
struct ProcessResult {
  bool started = false;  // false: not found or not executable
  int status = -1;       // exit status; 128 + the signal when killed
  std::string out, err;
};

// Runs argv (argv[0] looked up on the PATH) with stdin from /dev/null and our environment, in
// which `env`'s NAME=VALUE entries replace ours; collects stdout and stderr.
ProcessResult run_process(const std::vector<std::string>& argv, const std::vector<std::string>& env = {});

// The program's path if it is on the PATH, else "".
std::string find_on_path(const std::string& name);

}  // namespace passim
