; tools.g: creates no tool on disk; tests/lsp_test.py adds tool 1 in an unsaved edit
