;;; eglot_test.el --- the Emacs 28 + eglot client test of `rrflint server'  -*- lexical-binding: t -*-
;;
;; Run by tests/clients/run_client.sh as `emacs -Q --batch -l eglot_test.el', which copies tests/clients/card to
;; a scratch folder, puts rrflint on PATH and sets RRFLINT_CARD and RRFLINT_EDITORS_MD.
;;
;; It evaluates the "Emacs (eglot)" snippet of docs/editors.md as it stands there (so the documented set-up is what
;; is tested), visits the card's config.g, and checks through eglot and Flymake: the rule codes published for
;; config.g and for the macro it runs, one Flymake region (eglot turns the server's UTF-16 columns into Emacs
;; characters: after the emoji, which is two UTF-16 units but one character, the two differ), the quickfix code
;; actions, the buffer text after eglot applies the fix, the findings after the edit, and that killing the buffer
;; publishes empty lists.  Exits 0 when all hold; otherwise prints what failed and exits 1.  Every wait has a
;; deadline, and a global timer ends Emacs should anything else hang.

(require 'cl-lib)
(require 'subr-x)

(defconst rrf-test-wait 10 "Seconds any one answer of the server may take.")
(defconst rrf-test-global 60 "Seconds the whole test may take.")

(defun rrf-test-fail (fmt &rest args)
  (message "eglot_test: FAIL: %s" (apply #'format fmt args))
  (kill-emacs 1))

(run-at-time rrf-test-global nil
             (lambda () (rrf-test-fail "the test took longer than %d s" rrf-test-global)))

(defun rrf-test-check (cond fmt &rest args)
  (unless cond (error "%s" (apply #'format fmt args))))

(defun rrf-test-snippet (path heading)
  "The first ```elisp block after the heading HEADING in the Markdown file PATH."
  (with-temp-buffer
    (insert-file-contents path)
    (goto-char (point-min))
    (rrf-test-check (search-forward (concat "\n" heading) nil t) "no heading '%s' in %s" heading path)
    (rrf-test-check (search-forward "```elisp\n" nil t) "no ```elisp block after '%s' in %s" heading path)
    (let ((start (point)))
      (rrf-test-check (search-forward "\n```" nil t) "an unterminated block after '%s'" heading)
      (buffer-substring-no-properties start (match-beginning 0)))))

(defun rrf-test-eval-all (code)
  (with-temp-buffer
    (insert code)
    (goto-char (point-min))
    (condition-case nil
        (while t (eval (read (current-buffer)) t))
      (end-of-file nil))))

;; As at start-up: the installed packages are activated before the init file runs. Emacs 28 has eglot from
;; Debian's elpa-eglot, in the site-lisp folder that -Q leaves out; Emacs 29 and later have it built in. Without
;; eglot: exit 77, which run_client.sh reports as a skip (or, with CI=true, as a failure).
(require 'package)
(when (file-directory-p "/usr/share/emacs/site-lisp/elpa")
  (add-to-list 'package-directory-list "/usr/share/emacs/site-lisp/elpa"))
(package-initialize)
(unless (locate-library "eglot")
  (message "eglot_test: eglot is not installed")
  (kill-emacs 77))
(condition-case err
    (rrf-test-eval-all (rrf-test-snippet (getenv "RRFLINT_EDITORS_MD") "### Emacs (eglot)"))
  (error (rrf-test-fail "the snippet of docs/editors.md: %s" (error-message-string err))))

(require 'eglot)
(require 'flymake)

(defvar rrf-test-published nil
  "Every textDocument/publishDiagnostics of the server, newest first: (FILE . DIAGNOSTICS).")

(cl-defmethod eglot-handle-notification :before
  (_server (_method (eql textDocument/publishDiagnostics)) &key uri diagnostics &allow-other-keys)
  (push (cons (expand-file-name (eglot--uri-to-path uri)) diagnostics) rrf-test-published))

(defun rrf-test-codes (diagnostics)
  (string-join (sort (mapcar (lambda (d) (plist-get d :code)) diagnostics) #'string<) ","))

(defun rrf-test-wait-for (what pred)
  "Waits until PRED holds, processing the server's output; an error naming WHAT after `rrf-test-wait' s."
  (let ((deadline (+ (float-time) rrf-test-wait)))
    (while (and (not (funcall pred)) (< (float-time) deadline))
      (accept-process-output nil 0.02))
    (rrf-test-check (funcall pred) "waited %d s for %s" rrf-test-wait what)))

(defun rrf-test-wait-published (file want since)
  "Waits until the last publication for FILE, of those after the first SINCE, has the codes WANT."
  (rrf-test-wait-for
   (format "%s with [%s] (last published: %s)" file want
           (let ((last (assoc file rrf-test-published)))
             (if last (format "[%s]" (rrf-test-codes (append (cdr last) nil))) "nothing")))
   (lambda ()
     (let ((last (assoc file (butlast rrf-test-published since))))
       (and last (equal (rrf-test-codes (append (cdr last) nil)) want))))))

(defun rrf-test-flymake-codes ()
  (rrf-test-codes (mapcar (lambda (d) (alist-get 'eglot-lsp-diag (flymake-diagnostic-data d)))
                          (flymake-diagnostics))))

(defun rrf-test-range (range)
  "An LSP range as (START-LINE START-CHARACTER END-LINE END-CHARACTER)."
  (let ((start (plist-get range :start)) (end (plist-get range :end)))
    (list (plist-get start :line) (plist-get start :character) (plist-get end :line) (plist-get end :character))))

(defun rrf-test-region (diag)
  "DIAG's region as (LINE START-CHARACTER END-CHARACTER TEXT), characters counted from the line's start."
  (save-excursion
    (goto-char (flymake-diagnostic-beg diag))
    (let ((bol (line-beginning-position)))
      (list (line-number-at-pos) (- (flymake-diagnostic-beg diag) bol) (- (flymake-diagnostic-end diag) bol)
            (buffer-substring-no-properties (flymake-diagnostic-beg diag) (flymake-diagnostic-end diag))))))

(defun rrf-test-main ()
  (let* ((card (or (getenv "RRFLINT_CARD") (error "RRFLINT_CARD is not set (run tests/clients/run_client.sh)")))
         (config (expand-file-name "sys/config.g" card))
         (tools (expand-file-name "sys/tools.g" card))
         (buf (find-file-noselect config))
         server)
    (with-current-buffer buf
      (rrf-test-check (eq major-mode 'rrf-gcode-mode) "the snippet's mode for config.g is %s" major-mode)
      ;; eglot-ensure connects from `post-command-hook', at the end of the command that visited the file: batch
      ;; mode has no command loop, so the hook is run as the loop would run it.
      (run-hooks 'post-command-hook)
      (rrf-test-wait-for "eglot to manage config.g" (lambda () (and eglot--managed-mode (eglot-current-server))))
      (setq server (eglot-current-server))
      ;; Flymake starts checking a buffer when it is first shown in a window, and batch mode shows none: started
      ;; as showing the buffer would start it.
      (flymake-start)
      (let ((before (buffer-string)))
        ;; Visiting config.g lints its machine: config.g's findings, and the one in the macro it runs.
        (rrf-test-wait-published config "RRF104,RRF320" 0)
        (rrf-test-wait-published tools "RRF301" 0)
        (rrf-test-wait-for "Flymake to show RRF104 and RRF320"
                           (lambda () (equal (rrf-test-flymake-codes) "RRF104,RRF320")))
        ;; Line 7 is `M563 P0 S"Größe 😀 don't" …': the server's range starts at UTF-16 unit 22, which is
        ;; character 21 (the emoji is two units, one character); a column taken as characters would start at 22.
        (let* ((apos (cl-find-if (lambda (d) (equal (plist-get (alist-get 'eglot-lsp-diag (flymake-diagnostic-data d))
                                                                :code)
                                                    "RRF104"))
                                 (flymake-diagnostics)))
               (lsp (alist-get 'eglot-lsp-diag (flymake-diagnostic-data apos))))
          (rrf-test-check (equal (rrf-test-range (plist-get lsp :range)) '(6 22 6 24))
                          "RRF104's range from the server is %S" (plist-get lsp :range))
          (rrf-test-check (equal (rrf-test-region apos) '(7 21 23 "'t")) "Flymake's region for RRF104 is %S"
                          (rrf-test-region apos))
          ;; The quickfix actions there, as eglot asks for them; then eglot runs the fix (preferred) itself.
          (let* ((actions (eglot-code-actions (flymake-diagnostic-beg apos) (flymake-diagnostic-end apos) "quickfix"))
                 (titles (mapcar (lambda (a) (concat (plist-get a :title) (if (plist-get a :isPreferred) " (preferred)" "")))
                                 actions))
                 (since (length rrf-test-published)))
            (rrf-test-check (equal titles '("double the apostrophe (preferred)" "suppress RRF104 on this line"
                                            "suppress RRF104 in this file"))
                            "the code actions are %S" titles)
            (eglot--read-execute-code-action (list (car actions)) server "quickfix")
            (let ((after (replace-regexp-in-string "don't" "don''t" before t t)))
              (rrf-test-check (not (equal after before)) "the card's config.g has no \"don't\"")
              (rrf-test-check (equal (buffer-string) after) "the buffer after the fix is:\n%s" (buffer-string)))
            ;; eglot sends the edit (didChange) from an idle timer, and batch mode is never idle: sent as the
            ;; timer would send it. RRF104 is gone, the rest stays.
            (eglot--signal-textDocument/didChange)
            (rrf-test-wait-published config "RRF320" since)
            (rrf-test-wait-for "Flymake to show RRF320 alone" (lambda () (equal (rrf-test-flymake-codes) "RRF320")))))))
    ;; Killing the only buffer of the card: both files' findings are cleared.
    (let ((since (length rrf-test-published)))
      (kill-buffer buf)
      (rrf-test-wait-published config "" since)
      (rrf-test-wait-published tools "" since))
    ;; And the server stops cleanly when asked to.
    (eglot-shutdown server nil rrf-test-wait)
    (rrf-test-check (not (jsonrpc-running-p server)) "the server did not stop after shutdown and exit")
    ;; An extensionless macro is G-code by its folder.
    (let ((park (find-file-noselect (expand-file-name "macros/park" card))))
      (rrf-test-check (eq (buffer-local-value 'major-mode park) 'rrf-gcode-mode) "the snippet's mode for macros/park is %s"
                      (buffer-local-value 'major-mode park)))))

(let ((started (float-time)))
  (condition-case err
      (rrf-test-main)
    (error (rrf-test-fail "%s" (error-message-string err))))
  (message "eglot_test: OK (%.1f s)" (- (float-time) started))
  (kill-emacs 0))

;;; eglot_test.el ends here
