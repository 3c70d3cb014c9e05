// Which extensionless files the extension makes RRF G-code.
import * as assert from "node:assert/strict";
import { test } from "node:test";
import { isExtensionlessMacro } from "../files";

test("extensionless macros in sys/, macros/ and filaments/ are G-code", () => {
  for (const file of [
    "/card/sys/zLift",
    "/card/macros/Park",
    "/card/macros/Filament/Load Filament",
    "/card/filaments/PLA/purge",
    "/card/Macros/Park", // the SD card is case-insensitive
    "/home/me/printers/voron/sys/Endscript",
  ]) {
    assert.equal(isExtensionlessMacro(file, "/"), true, file);
  }
});

test("files with an extension, or outside those folders, are left to VS Code", () => {
  for (const file of [
    "/card/sys/config.json",
    "/card/sys/heightmap.csv",
    "/card/sys/.rrflint.toml",
    "/card/macros/README.md",
    "/card/macros/notes.txt",
    "/card/filaments/PLA/load.g", // .g: the language's own extension
    "/card/gcodes/Park",
    "/card/sys/sub/thing", // only sys/ itself holds system macros
    "/card/Makefile",
    "/",
  ]) {
    assert.equal(isExtensionlessMacro(file, "/"), false, file);
  }
});

test("Windows paths", () => {
  assert.equal(isExtensionlessMacro("C:\\card\\macros\\Park", "\\"), true);
  assert.equal(isExtensionlessMacro("C:\\card\\macros\\Park.txt", "\\"), false);
});
