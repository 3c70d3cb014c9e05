// Which files are RRF G-code besides `*.g`: the extensionless macros RRF runs from the SD card's sys/, macros/ and
// filaments/ folders (Duet Web Control creates macros without an extension). VS Code's filenamePatterns cannot say
// "a name without a dot" (and a pattern such as **/macros/** would beat every extension, making macros/README.md
// G-code), so the extension gives these files the language itself when VS Code opens them as plain text.
import * as path from "path";

const FOLDERS = new Set(["sys", "macros", "filaments"]);

/**
 * True when `file` has no dot in its name and lies in a sys/ folder, or anywhere below a macros/ or filaments/
 * folder (folder names compared case-insensitively, as on the SD card). `file` is an absolute path.
 */
export function isExtensionlessMacro(file: string, sep: string = path.sep): boolean {
  const parts = file.split(sep === "\\" ? /[\\/]/ : "/").filter((p) => p !== "");
  const name = parts.pop();
  if (name === undefined || name.includes(".")) {
    return false;
  }
  const folders = parts.map((p) => p.toLowerCase());
  if (folders.length > 0 && folders[folders.length - 1] === "sys") {
    return true;
  }
  return folders.some((f) => f !== "sys" && FOLDERS.has(f));
}
