// The renderer settings the process decides, not the renderer: walk-shader override, thread priority.
#pragma once

namespace vots::render {
class VotRenderer;
}

namespace vots::server {

/// For `vots render` and the server's render thread alike: VOTS_WALK_SHADER=fragment|compute overrides
/// the renderer's choice by GL renderer and has the walk draw the MIP, where a CPU rasteriser's default
/// is the splat (another value is ignored with a warning on stderr), and the
/// threads the renderer starts for work no frame waits for (skip-box growth) run at SCHED_IDLE, so they
/// never slow a fit or a frame someone is waiting for.
void applyRenderPolicy(render::VotRenderer& renderer);

} // namespace vots::server
