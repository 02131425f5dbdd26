// A host application that runs a scene file (snh/scene.h): load it, take
// its solve options, run it with a line per load step or frame, and write
// its JSON summary.
//   scene_file SCENE.json SUMMARY.json
#include <iostream>

#include "snh/error.h"
#include "snh/scene.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: scene_file SCENE.json SUMMARY.json\n";
    return 2;
  }
  try {
    const snh::SceneFile file = snh::load_scene(argv[1]);
    snh::SceneRunOptions run;
    run.progress = [](const snh::SceneProgress& p) {
      std::cout << (p.frame ? "frame " : "step ") << p.index << "/" << p.count << ": " << p.newton_iterations
                << " Newton, " << p.cg_iterations << " CG\n";
    };
    const snh::SceneRun result = snh::run_scene(file, file.scene.options, run);
    snh::write_scene_json(argv[2], file, result);
    std::cout << file.scene.name << ": converged " << (result.converged ? "yes" : "no") << '\n';
    return result.converged ? 0 : 1;
  } catch (const snh::Error& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 2;
  }
}
