-- wrk script: every /render request asks for a camera angle no earlier request used, so the server's
-- frame cache and shared renders cannot answer it and each request is a real frame.
-- The URL given to wrk must be a /render URL without cam=.
local threads = 0

function setup(thread)
    thread:set("id", threads)
    threads = threads + 1
end

function init(args)
    n = id * 1000000
end

function request()
    n = n + 1
    local az = (n % 1000000) * 0.0007 - 180 -- distinct to the 4th decimal for 514,000 requests per thread
    local el = 20 + id * 0.1
    return wrk.format(nil, wrk.path .. string.format("&cam=az%%3D%.4f%%2Cel%%3D%.1f", az, el))
end
