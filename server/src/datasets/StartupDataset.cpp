// The start-up dataset (`vots serve --prepare`), readied as the server starts: its volume loaded, its
// default fit done and uploaded to the renderer, so that the viewer's first image does not wait for them.
#include "ServerImpl.h"
#include "frames/RenderFrames.h"

#include <chrono>
#include <iostream>

namespace vots::server {

void readyStartupDataset(Server::Impl& s, const std::string& name) {
    try {
        const auto dataset = s.registry.find(name);
        if (s.options.ranks && dataset->kind == DatasetKind::Vots) {
            // Under mpirun a first frame has every rank read the file and upload its Vots of it.
            RenderParams first;
            first.dataset = name;
            first.width = first.height = 1;
            s.renderQueue->render(prepareRender(s, first, "").job);
            return;
        }
        std::shared_ptr<const fit::VotSpace> space = dataset->space; // a .vots dataset has it loaded
        if (dataset->kind == DatasetKind::Volume) {
            // The viewer's first fit.
            const FitKey key = fitKeyFor(*dataset, EpsSpec{}, DEFAULT_DEGREE, s.options.fitNorm);
            const auto fit = s.fitJobs.submit(dataset, key);
            (void)fit->waitFinished(std::chrono::minutes(10)); // failed: the job says why
            // The fit job has had the render thread upload its Vot-Space as it ended (uploadAhead); under
            // mpirun the ranks hold their fit and the first frame uploads it.
            return;
        }
        uploadAhead(s, *dataset, std::move(space), true);
    } catch (const std::exception& e) {
        // Nothing is lost: the first request for the dataset will load and fit it, and say what fails.
        std::cerr << "vots serve: could not prepare dataset '" << name << "': " << e.what() << "\n";
    }
}

} // namespace vots::server
