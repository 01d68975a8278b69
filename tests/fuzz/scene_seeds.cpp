// Writes the scene JSON seed corpus for scene_json_fuzz (run by make_corpus.sh):
// every built-in reference scene as scene_to_json writes it, so the fuzzer
// starts from documents that exercise every primitive kind, the light, both
// cameras and the map size.
//
//   scene_seeds OUT_DIR
#include <cstdio>
#include <fstream>
#include <string>

#include "penumbra/reference/scene.h"

int main(int argc, char** argv)
{
    if (argc != 2) {
        std::fprintf(stderr, "usage: scene_seeds OUT_DIR\n");
        return 2;
    }
    int written = 0;
    for (const std::string& name : penumbra::reference::builtin_scene_names(penumbra::reference::SceneSet::All)) {
        std::ofstream out(std::string(argv[1]) + "/" + name + ".json", std::ios::binary);
        out << penumbra::reference::scene_to_json(penumbra::reference::builtin_scene(name));
        if (!out.flush()) {
            std::fprintf(stderr, "scene_seeds: cannot write %s/%s.json\n", argv[1], name.c_str());
            return 1;
        }
        ++written;
    }
    std::printf("%d scene seeds in %s\n", written, argv[1]);
    return 0;
}
