// applyRenderPolicy: reads VOTS_WALK_SHADER (the walk, in that stage) and lowers the renderer's background
// threads to idle priority.
#include "vots/server/RenderPolicy.h"

#include "vots/render/VotRenderer.h"
#include "vots/server/ThreadPriority.h"

#include <cstdlib>
#include <iostream>

namespace vots::server {

void applyRenderPolicy(render::VotRenderer& renderer) {
    // The compute walk is the default on GPUs, the CPU splat on a CPU rasteriser; the override lets a
    // person compare them: naming a walk stage has the walk draw the MIP too.
    if (const char* forced = std::getenv("VOTS_WALK_SHADER")) {
        if (const auto shader = render::parseWalkShader(forced)) {
            renderer.setWalkShader(*shader);
            renderer.setStrategy(render::VotRenderer::Strategy::Walk);
        } else
            std::cerr << "vots: warning: VOTS_WALK_SHADER=" << forced
                      << " is neither fragment nor compute; choosing by renderer\n";
    }
    renderer.setBackgroundThreadStart(lowerThisThreadToIdle);
}

} // namespace vots::server
