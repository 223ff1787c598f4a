// The translation unit the stages' precompiled header is built with; it holds nothing of its own.
