// Placeholder: replaced by the module author.
