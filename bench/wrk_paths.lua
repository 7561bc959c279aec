-- wrk script: requests the paths listed one per line in the file named by the environment
-- variable HEXLOD_PATHS, in turn, each wrk thread starting at another offset.
local paths = {}
local counter = 0

function init(args)
    for line in io.lines(os.getenv("HEXLOD_PATHS")) do
        paths[#paths + 1] = line
    end
    counter = math.random(#paths)
end

function request()
    counter = counter % #paths + 1
    return wrk.format("GET", paths[counter])
end
