-- wrk script: POST one program file (NCPOST_BENCH_FILE) to the target URL, body read once.
local path = os.getenv("NCPOST_BENCH_FILE")
local f = assert(io.open(path, "rb"))
wrk.method = "POST"
wrk.body = f:read("*a")
f:close()
wrk.headers["Content-Type"] = "application/octet-stream"

