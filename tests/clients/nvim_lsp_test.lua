-- The neovim 0.7 client test of `rrflint server`: run as the init file of a headless neovim by
-- tests/clients/run_client.sh (which copies tests/clients/card to a scratch folder, puts rrflint on PATH and
-- sets RRFLINT_CARD and RRFLINT_EDITORS_MD).
--
-- It runs the "Neovim 0.7" snippet of docs/editors.md as it stands there (so the documented set-up is what is
-- tested), opens the card's config.g, and checks through neovim's own LSP client: the rule codes published for
-- config.g and for the macro it runs, one range in UTF-16 units after non-ASCII text (and the byte columns neovim
-- turns it into), the quickfix code actions, the buffer text after applying the fix, the findings after the
-- edit, and that closing the buffer publishes empty lists. Exits 0 when all hold; otherwise prints what failed
-- and exits 1. Every wait has a deadline, and a global timer ends neovim should anything else hang.
local WAIT_MS = 10000 -- any one answer of the server
local GLOBAL_MS = 60000 -- the whole test

local function fail(msg)
  io.stderr:write("nvim_lsp_test: FAIL: " .. msg .. "\n")
  vim.cmd("cquit 1")
end

local function check(cond, msg)
  if not cond then
    error(msg, 0)
  end
end

-- The first ```lua block after the heading `heading` in the Markdown file `path`.
local function snippet(path, heading)
  local f = io.open(path, "r")
  check(f, "cannot read " .. tostring(path))
  local text = f:read("*a")
  f:close()
  local at = text:find("\n" .. heading, 1, true)
  check(at, "no heading '" .. heading .. "' in " .. path)
  local code = text:match("```lua\n(.-)\n```", at)
  check(code, "no ```lua block after '" .. heading .. "' in " .. path)
  return code
end

-- Every textDocument/publishDiagnostics the server sends, in order: { uri = ..., codes = {...}, diagnostics }.
local published = {}
local default_publish = vim.lsp.handlers["textDocument/publishDiagnostics"]
vim.lsp.handlers["textDocument/publishDiagnostics"] = function(err, result, ctx, config)
  table.insert(published, { uri = result.uri, diagnostics = result.diagnostics })
  return default_publish(err, result, ctx, config)
end

local function codes(diagnostics)
  local out = {}
  for _, d in ipairs(diagnostics) do
    table.insert(out, d.code)
  end
  table.sort(out)
  return table.concat(out, ",")
end

-- The diagnostics of the last publication for `uri` after the first `from` ones, once it has the codes `want`
-- (a comma-separated sorted list; "" for none).
local function wait_for(uri, want, from, what)
  local found
  local ok = vim.wait(WAIT_MS, function()
    for i = #published, from + 1, -1 do
      if published[i].uri == uri then
        found = published[i]
        return codes(found.diagnostics) == want
      end
    end
    return false
  end, 20)
  check(ok, string.format("%s: waited %d ms for %s with [%s]; last published: %s", what, WAIT_MS, uri, want,
    found and "[" .. codes(found.diagnostics) .. "]" or "nothing"))
  return found.diagnostics
end

local function by_code(diagnostics, code)
  for _, d in ipairs(diagnostics) do
    if d.code == code then
      return d
    end
  end
  error("no " .. code .. " among " .. codes(diagnostics), 0)
end

local function same(a, b)
  return vim.deep_equal(a, b)
end

local function main()
  local card = os.getenv("RRFLINT_CARD")
  check(card and card ~= "", "RRFLINT_CARD is not set (run tests/clients/run_client.sh)")
  local config_path = card .. "/sys/config.g"
  local config = vim.uri_from_fname(config_path)
  local tools = vim.uri_from_fname(card .. "/sys/tools.g")

  vim.cmd("edit " .. vim.fn.fnameescape(config_path))
  local buf = vim.api.nvim_get_current_buf()
  check(vim.bo[buf].filetype == "gcode", "the snippet's filetype for config.g is '" .. vim.bo[buf].filetype .. "'")
  local before = vim.api.nvim_buf_get_lines(buf, 0, -1, true)

  -- Opening config.g lints its machine: config.g's findings, and the one in the macro it runs.
  local diags = wait_for(config, "RRF104,RRF320", 0, "after opening config.g")
  wait_for(tools, "RRF301", 0, "after opening config.g")
  local clients = vim.lsp.buf_get_clients(buf)
  local client
  for _, c in pairs(clients) do
    client = c
  end
  check(client and client.name == "rrflint" and #vim.tbl_keys(clients) == 1, "config.g has not exactly one client, rrflint")

  -- Line 7 is `M563 P0 S"Größe 😀 don't" …`: the apostrophe is the 22nd character, after 21 code points that
  -- are 22 UTF-16 units (the emoji takes two) and 26 bytes ('ö' and 'ß' two each, the emoji four).
  local apos = by_code(diags, "RRF104")
  check(same(apos.range, { start = { line = 6, character = 22 }, ["end"] = { line = 6, character = 24 } }),
    "RRF104's range is " .. vim.inspect(apos.range))
  local shown = vim.diagnostic.get(buf, { lnum = 6 })
  check(#shown == 1 and shown[1].code == "RRF104" and shown[1].col == 26 and shown[1].end_col == 28,
    "neovim shows line 7's findings as " .. vim.inspect(shown))

  -- The quickfix actions at the finding: the fix (preferred) and the two suppressions.
  vim.api.nvim_win_set_cursor(0, { 7, 26 })
  local params = vim.lsp.util.make_range_params(0, client.offset_encoding)
  check(same(params.range.start, { line = 6, character = 22 }), "the cursor's position is " .. vim.inspect(params.range))
  params.context = { diagnostics = { apos }, only = { "quickfix" } }
  local answers, err = vim.lsp.buf_request_sync(buf, "textDocument/codeAction", params, WAIT_MS)
  check(answers, "textDocument/codeAction: " .. tostring(err))
  local actions = answers[client.id] and answers[client.id].result or {}
  local titles = {}
  for _, a in ipairs(actions) do
    table.insert(titles, a.title .. (a.isPreferred and " (preferred)" or ""))
  end
  check(same(titles, { "double the apostrophe (preferred)", "suppress RRF104 on this line", "suppress RRF104 in this file" }),
    "the code actions are " .. vim.inspect(titles))

  local from = #published
  vim.lsp.util.apply_workspace_edit(actions[1].edit, client.offset_encoding)
  local after = vim.deepcopy(before)
  after[7] = [[M563 P0 S"Größe 😀 don''t" D0 H1 ; tool 0]]
  check(same(vim.api.nvim_buf_get_lines(buf, 0, -1, true), after),
    "the buffer after the fix is:\n" .. table.concat(vim.api.nvim_buf_get_lines(buf, 0, -1, true), "\n"))
  -- The edit reaches the server (didChange): RRF104 is gone, the rest stays.
  wait_for(config, "RRF320", from, "after the fix")

  -- Closing the only open buffer of the card: both files' findings are cleared.
  from = #published
  vim.cmd("bdelete! " .. buf)
  wait_for(config, "", from, "after closing config.g")
  wait_for(tools, "", from, "after closing config.g")

  -- An extensionless macro is G-code by its folder, and the snippet attaches the client it already started.
  vim.cmd("edit " .. vim.fn.fnameescape(card .. "/macros/park"))
  local park = vim.api.nvim_get_current_buf()
  check(vim.bo[park].filetype == "gcode", "the snippet's filetype for macros/park is '" .. vim.bo[park].filetype .. "'")
  local attached = vim.tbl_keys(vim.lsp.buf_get_clients(park))
  check(same(attached, { client.id }), "macros/park has the clients " .. vim.inspect(attached) .. ", not " .. client.id)
  check(#vim.lsp.get_active_clients() == 1, "the snippet started a second server")

  -- And the server stops cleanly when asked to.
  vim.lsp.stop_client(client.id)
  check(vim.wait(WAIT_MS, function()
    return vim.lsp.get_client_by_id(client.id) == nil
  end, 20), "the server did not stop after shutdown and exit")
end

-- The documented set-up, run as an init file would run it: before the file types load.
local ok, err = pcall(function()
  local code = snippet(os.getenv("RRFLINT_EDITORS_MD") or "", "### Neovim 0.7")
  local chunk, perr = loadstring(code, "docs/editors.md (Neovim 0.7)")
  check(chunk, tostring(perr))
  chunk()
end)
if not ok then
  fail("the snippet of docs/editors.md: " .. tostring(err))
end

vim.defer_fn(function()
  fail(string.format("the test took longer than %d ms", GLOBAL_MS))
end, GLOBAL_MS)

-- After start-up, outside any autocommand (within one, opening config.g would fire no FileType event).
vim.api.nvim_create_autocmd("VimEnter", {
  once = true,
  callback = vim.schedule_wrap(function()
    local started = vim.loop.hrtime()
    local ok2, err2 = pcall(main)
    if not ok2 then
      fail(tostring(err2))
      return
    end
    io.stdout:write(string.format("nvim_lsp_test: OK (%.1f s)\n", (vim.loop.hrtime() - started) / 1e9))
    vim.cmd("qall!")
  end),
})
